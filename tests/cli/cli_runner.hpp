#pragma once
// Runs the `mrd` binary as a user would and captures what it printed.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

namespace mrd::test {

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

/// Every regular file under `dir` (path relative to it) with its bytes.
using Snapshot = std::map<std::string, std::string>;
inline Snapshot snapshot(const std::filesystem::path& dir) {
  Snapshot s;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) s[std::filesystem::relative(e.path(), dir).string()] = slurp(e.path());
  }
  return s;
}

/// The names in the folder `dir`.
inline std::set<std::string> entries(const std::filesystem::path& dir) {
  std::set<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

/// A fresh temporary folder per test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "mrd-test-XXXXXX").string();
    path_ = ::mkdtemp(tmpl.data());
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// Runs the shell command line `line` with its stdout and stderr kept in
/// `scratch` (stdout.txt, stderr.txt) and read back.
inline RunResult run_command(const std::string& line, const std::filesystem::path& scratch) {
  const auto out = scratch / "stdout.txt";
  const auto err = scratch / "stderr.txt";
  const int status = std::system((line + " >" + out.string() + " 2>" + err.string()).c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

/// `args` is appended to the binary path as shell words; the program runs in
/// `cwd` when one is given (its output is kept in `scratch` either way), and
/// is killed after `kill_after_s` seconds when that is above 0 (so that a
/// program that blocks fails a test instead of hanging it).
inline RunResult run_mrd(const std::string& args, const std::filesystem::path& scratch,
                         const std::filesystem::path& cwd = {}, int kill_after_s = 0) {
  const std::string cd = cwd.empty() ? std::string() : "cd '" + cwd.string() + "' && ";
  const std::string limit = kill_after_s > 0 ? "timeout -s KILL " + std::to_string(kill_after_s) + " " : std::string();
  return run_command(cd + limit + std::string(MRD_BINARY) + " " + args, scratch);
}

inline int count_lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

}  // namespace mrd::test
