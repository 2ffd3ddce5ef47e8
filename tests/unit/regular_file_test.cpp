// The reader policy (firmware/platform/linux/regular_file): a regular file is
// read whole within its limit; a FIFO (with no writer: a plain open() would
// block for ever), a folder, a device or a socket is refused before any read,
// promptly, with the wording every program prints after "<file>: ".
#include "firmware/platform/linux/regular_file.hpp"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>
#include <fcntl.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <string>

namespace mrd::posix {
namespace {
namespace fs = std::filesystem;

class RegularFile : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "mrd-regular-XXXXXX").string();
    ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path write(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return dir_ / name;
  }
  fs::path fifo(const std::string& name) const {
    const fs::path p = dir_ / name;
    EXPECT_EQ(::mkfifo(p.c_str(), 0600), 0) << std::strerror(errno);
    return p;
  }
  /// Reads `path` as text on another thread: a read that blocks fails the test
  /// after 5 s instead of hanging it (a writer is then opened to release it).
  FileCheck read_within_5_s(const fs::path& path, std::size_t max_bytes, std::string& text) const {
    auto pending = std::async(std::launch::async, [&] { return read_regular_file(path.c_str(), max_bytes, text); });
    if (pending.wait_for(std::chrono::seconds(5)) != std::future_status::ready) {
      ADD_FAILURE() << path << ": the read blocked";
      const int w = ::open(path.c_str(), O_WRONLY | O_NONBLOCK);
      if (w >= 0) ::close(w);
    }
    return pending.get();
  }
  fs::path dir_;
};

TEST_F(RegularFile, ARegularFileIsReadWholeUpToItsLimit) {
  const fs::path p = write("ten.txt", "0123456789");
  std::string text;
  EXPECT_TRUE(read_regular_file(p.c_str(), 10, text).ok());
  EXPECT_EQ(text, "0123456789");
  const FileCheck over = read_regular_file(p.c_str(), 9, text);
  EXPECT_EQ(over.problem, FileProblem::kTooLarge);
  EXPECT_EQ(problem_text(over, 9), "10 bytes, larger than the limit of 9 bytes");
  EXPECT_EQ(problem_text(over, std::size_t{2} << 20), "10 bytes, larger than the limit of 2 MiB");
}

TEST_F(RegularFile, TheBufferReaderTellsExactlyTheLimitFromOneByteMore) {
  std::uint8_t buf[4] = {};
  std::size_t got = 99;
  EXPECT_TRUE(read_regular_file(write("four", "abcd").c_str(), buf, sizeof buf, got).ok());
  EXPECT_EQ(got, 4u);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(buf), 4), "abcd");
  EXPECT_TRUE(read_regular_file(write("two", "ab").c_str(), buf, sizeof buf, got).ok());
  EXPECT_EQ(got, 2u);
  EXPECT_EQ(read_regular_file(write("five", "abcde").c_str(), buf, sizeof buf, got).problem, FileProblem::kTooLarge);
  EXPECT_TRUE(read_regular_file(write("empty", "").c_str(), buf, sizeof buf, got).ok());
  EXPECT_EQ(got, 0u);
}

TEST_F(RegularFile, AFifoWithNoWriterIsRefusedAtOnce) {
  const fs::path p = fifo("pipe");
  std::string text;
  const FileCheck c = read_within_5_s(p, 1 << 20, text);
  EXPECT_EQ(c.problem, FileProblem::kPipe);
  EXPECT_EQ(problem_text(c, 1 << 20), "is a pipe (FIFO), expected a regular file");
  std::uint8_t buf[64];
  std::size_t got = 0;
  EXPECT_EQ(read_regular_file(p.c_str(), buf, sizeof buf, got).problem, FileProblem::kPipe);
}

TEST_F(RegularFile, AFolderADeviceAndASocketAreRefused) {
  std::string text;
  const FileCheck folder = read_within_5_s(dir_, 1 << 20, text);
  EXPECT_EQ(folder.problem, FileProblem::kFolder);
  EXPECT_EQ(problem_text(folder, 1 << 20), "is a folder, expected a regular file");
  // /dev/zero would fill any limit; it is refused unread.
  const FileCheck zero = read_within_5_s("/dev/zero", 1 << 20, text);
  EXPECT_EQ(zero.problem, FileProblem::kDevice);
  EXPECT_EQ(problem_text(zero, 1 << 20), "is a device, expected a regular file");
  EXPECT_TRUE(text.empty());

  const fs::path sock = dir_ / "sock";
  const int s = ::socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(s, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  ASSERT_LT(sock.string().size(), sizeof addr.sun_path);
  std::strcpy(addr.sun_path, sock.c_str());
  ASSERT_EQ(::bind(s, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0) << std::strerror(errno);
  const FileCheck socket_check = read_within_5_s(sock, 1 << 20, text);
  ::close(s);
  EXPECT_EQ(socket_check.problem, FileProblem::kNotRegular);
  EXPECT_EQ(problem_text(socket_check, 1 << 20), "is not a regular file");
}

TEST_F(RegularFile, AMissingFileIsNamedAndALinkToAFileIsRead) {
  std::string text;
  const FileCheck missing = read_regular_file((dir_ / "none").c_str(), 100, text);
  EXPECT_EQ(missing.problem, FileProblem::kMissing);
  EXPECT_EQ(problem_text(missing, 100), "file not found");
  fs::create_symlink(write("target", "xyz"), dir_ / "link");
  EXPECT_TRUE(read_regular_file((dir_ / "link").c_str(), 100, text).ok());
  EXPECT_EQ(text, "xyz");
}

TEST_F(RegularFile, CheckWithoutReadingGivesTheSameVerdicts) {
  EXPECT_TRUE(check_regular_file(write("a", "abc").c_str(), 3).ok());
  EXPECT_EQ(check_regular_file((dir_ / "a").c_str(), 2).problem, FileProblem::kTooLarge);
  EXPECT_EQ(check_regular_file(fifo("p").c_str(), 100).problem, FileProblem::kPipe);
  EXPECT_EQ(check_regular_file(dir_.c_str(), 100).problem, FileProblem::kFolder);
  EXPECT_EQ(check_regular_file("/dev/null", 100).problem, FileProblem::kDevice);
  EXPECT_EQ(check_regular_file((dir_ / "none").c_str(), 100).problem, FileProblem::kMissing);
}

// A state file is read and replaced: absent or regular is fine, anything else is named.
TEST_F(RegularFile, NonRegularProblemNamesOnlyWhatExistsAsSomethingElse) {
  EXPECT_EQ(non_regular_problem((dir_ / "none").string()), "");
  EXPECT_EQ(non_regular_problem(write("big", std::string(100000, 'x')).string()), "") << "no size limit";
  EXPECT_EQ(non_regular_problem(dir_.string()), "is a folder, expected a regular file");
  EXPECT_EQ(non_regular_problem(fifo("p").string()), "is a pipe (FIFO), expected a regular file");
  EXPECT_EQ(non_regular_problem("/dev/null"), "is a device, expected a regular file");
}

}  // namespace
}  // namespace mrd::posix
