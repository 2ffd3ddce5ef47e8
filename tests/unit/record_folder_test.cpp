// The records of a folder (--records DIR): hidden names skipped, a record
// name that is not a regular file refused by name, other names ignored.
#include "host_sim/excitation/record_folder.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "host_sim/io/usage_error.hpp"

namespace mrd::excitation {
namespace {
namespace fs = std::filesystem;

class RecordFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "mrd-records-XXXXXX").string();
    if (::mkdtemp(tmpl.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    dir_ = tmpl;
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  void file(const std::string& name) const { std::ofstream(dir_ / name) << "time_s,accel_m_s2\n0,0\n0.01,1\n"; }
  void fifo(const std::string& name) const { ASSERT_EQ(::mkfifo((dir_ / name).c_str(), 0600), 0); }
  /// The error record_files_in_folder gives, or "" when it accepts the folder.
  std::string error() const {
    try {
      (void)record_files_in_folder("--records", dir_);
    } catch (const io::UsageError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(RecordFolder, TakesRecordNamesOfAnyCaseSortedAndSkipsHiddenAndOtherNames) {
  file("b.csv");
  file("A.AT2");
  file("c.Csv");
  std::ofstream(dir_ / ".junk.csv") << "not a record";  // hidden: skipped, not read
  fifo(".pipe.csv");                                   // hidden, even when it would block
  file("notes.txt");
  fifo("pipe");  // no record extension: not a record
  fs::create_directory(dir_ / "sub");
  const auto files = record_files_in_folder("--records", dir_);
  const std::vector<fs::path> expected{dir_ / "A.AT2", dir_ / "b.csv", dir_ / "c.Csv"};
  EXPECT_EQ(files, expected);
}

TEST_F(RecordFolder, RecordNameThatIsNotARegularFileIsAnErrorNamingIt) {
  file("a.csv");
  fifo("quake.csv");
  std::string e = error();
  EXPECT_NE(e.find("--records: '" + (dir_ / "quake.csv").string() + "' is a FIFO"), std::string::npos) << e;
  fs::remove(dir_ / "quake.csv");

  fs::create_directory(dir_ / "old.AT2");
  e = error();
  EXPECT_NE(e.find("old.AT2' is a folder"), std::string::npos) << e;
  fs::remove(dir_ / "old.AT2");

  fs::create_symlink("/dev/null", dir_ / "null.csv");
  e = error();
  EXPECT_NE(e.find("null.csv' is a device"), std::string::npos) << e;
  fs::remove(dir_ / "null.csv");

  fs::create_symlink(dir_ / "missing.csv", dir_ / "gone.csv");
  e = error();
  EXPECT_NE(e.find("gone.csv' is a broken link"), std::string::npos) << e;
  fs::remove(dir_ / "gone.csv");

  fs::create_symlink(dir_ / "a.csv", dir_ / "link.csv");  // a link to a record is a record
  EXPECT_EQ(error(), "");
}

TEST_F(RecordFolder, FolderWithoutRecordsOrNotAFolder) {
  file(".hidden.csv");
  file("readme.txt");
  EXPECT_NE(error().find("no .csv or .at2 record in"), std::string::npos);
  file("x.csv");
  EXPECT_THROW((void)record_files_in_folder("--records", dir_ / "x.csv"), io::UsageError);
  EXPECT_THROW((void)record_files_in_folder("--records", dir_ / "absent"), io::UsageError);
}

}  // namespace
}  // namespace mrd::excitation
