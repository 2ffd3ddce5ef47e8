#include "host_sim/report/output_transaction.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <signal.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <array>
#include <cstddef>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <string>
#include <system_error>
#include <vector>

#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"
#include "host_sim/report/path_ownership.hpp"

namespace mrd::report {
namespace fs = std::filesystem;
using io::UsageError;

namespace {

// ------------------------------------------------ what a signal handler sees

/// Open transactions' staging folders as plain strings, for the signal handler
/// (which may only use async-signal-safe calls). An empty slot is unused.
constexpr std::size_t kMaxOpen = 8;
constexpr std::size_t kMaxPath = 4096;
char g_staging[kMaxOpen][kMaxPath];
volatile std::sig_atomic_t g_in_use[kMaxOpen];

constexpr std::array kCleanupSignals{SIGINT, SIGTERM, SIGHUP, SIGQUIT};

bool is_dot_or_dotdot(const char* n) { return n[0] == '.' && (n[1] == '\0' || (n[1] == '.' && n[2] == '\0')); }

/// The fixed head of a getdents64 record (linux_dirent64); the
/// NUL-terminated name follows it at kDirentNameOffset.
struct LinuxDirent64Head {
  ino64_t d_ino;
  off64_t d_off;
  unsigned short d_reclen;
  unsigned char d_type;
};
constexpr std::size_t kDirentNameOffset = offsetof(LinuxDirent64Head, d_type) + 1;

/// Removes `name` under the folder `parent_fd`, recursively, with
/// async-signal-safe calls only (openat, getdents64, unlinkat, close).
void remove_tree_signal_safe(int parent_fd, const char* name, int depth) {
  if (::unlinkat(parent_fd, name, 0) == 0 || errno == ENOENT) return;
  if (depth > 32) return;
  const int fd = ::openat(parent_fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return;
  for (int pass = 0; pass < 4; ++pass) {
    ::lseek(fd, 0, SEEK_SET);
    alignas(8) char buf[2048];
    for (;;) {
      const long n = ::syscall(SYS_getdents64, fd, buf, sizeof buf);
      if (n <= 0) break;
      for (long off = 0; off < n;) {
        const auto* d = reinterpret_cast<const LinuxDirent64Head*>(buf + off);
        const char* entry = buf + off + kDirentNameOffset;
        off += d->d_reclen;
        if (!is_dot_or_dotdot(entry)) remove_tree_signal_safe(fd, entry, depth + 1);
      }
    }
    if (::unlinkat(parent_fd, name, AT_REMOVEDIR) == 0 || errno != ENOTEMPTY) break;
  }
  ::close(fd);
}

extern "C" void remove_staging_and_reraise(int sig) {
  const int saved = errno;
  for (std::size_t i = 0; i < kMaxOpen; ++i) {
    if (g_in_use[i] != 0) remove_tree_signal_safe(AT_FDCWD, g_staging[i], 0);
  }
  errno = saved;
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

void install_handlers_once() {
  static bool installed = false;
  if (installed) return;
  installed = true;
  for (const int sig : kCleanupSignals) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue;  // keep an ignored signal ignored
    struct sigaction sa {};
    sa.sa_handler = remove_staging_and_reraise;
    sigemptyset(&sa.sa_mask);
    for (const int s : kCleanupSignals) sigaddset(&sa.sa_mask, s);
    ::sigaction(sig, &sa, nullptr);
  }
}

/// Blocks the cleanup signals for its lifetime (the swap must not be cut in two).
class SignalBlock {
 public:
  SignalBlock() {
    sigset_t set;
    sigemptyset(&set);
    for (const int s : kCleanupSignals) sigaddset(&set, s);
    ::pthread_sigmask(SIG_BLOCK, &set, &old_);
  }
  ~SignalBlock() { ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  SignalBlock(const SignalBlock&) = delete;
  SignalBlock& operator=(const SignalBlock&) = delete;

 private:
  sigset_t old_{};
};

void publish(std::size_t slot, const fs::path& staging) {
  g_in_use[slot] = 0;
  std::snprintf(g_staging[slot], kMaxPath, "%s", staging.c_str());
  g_in_use[slot] = 1;
}

// ------------------------------------------------------------ transactions

struct Transaction {
  fs::path shown;  ///< the folder as the user named it
  fs::path target;
  fs::path staging;
  fs::path created_root;  ///< first parent folder this run created; empty if none
  std::size_t slot = 0;
};

struct Registry {
  std::vector<Transaction> open;
  std::vector<Transaction> committed;  ///< for shown_path after the commit
  ~Registry() { abandon_outputs(); }
};

Registry& registry() {
  static Registry r;
  return r;
}

/// "." + name + suffix, built by appending (GCC 12's -Wrestrict misreads the
/// inlined `const char* + std::string&&` at -O3).
std::string hidden_name(const fs::path& target, const char* suffix) {
  std::string s(".");
  s += target.filename().string();
  s += suffix;
  return s;
}

std::string staging_prefix(const fs::path& target) { return hidden_name(target, ".staging-"); }
std::string old_prefix(const fs::path& target) { return hidden_name(target, ".old-"); }

/// Removes the folder `dir` of a result with its marker last: a kill in the
/// middle leaves the marker in place, so the next run still knows the rest
/// for this program's and removes it (remove_stale_staging removes only
/// folders that hold the marker or are empty). Errors are left in `ec`.
void remove_marked_tree(const fs::path& dir, std::error_code& ec) {
  ec.clear();
  std::error_code it_ec;
  std::vector<fs::path> rest;
  for (fs::directory_iterator it(dir, it_ec), end; !it_ec && it != end; it.increment(it_ec)) {
    if (it->path().filename() != kResultMarker) rest.push_back(it->path());
  }
  for (const fs::path& p : rest) {
    std::error_code rm;
    fs::remove_all(p, rm);
    if (rm && !ec) ec = rm;
  }
  std::error_code rm;
  fs::remove_all(dir, rm);
  if (rm && !ec) ec = rm;
}

bool process_gone(const std::string& pid_text) {
  if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos || pid_text.size() > 9) {
    return false;
  }
  const pid_t pid = static_cast<pid_t>(std::stol(pid_text));
  return pid > 0 && pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH;
}

/// Removes staging (and set-aside) folders of `target` left by processes that
/// were killed (SIGKILL cannot be caught).
void remove_stale_staging(const fs::path& target) {
  std::error_code ec;
  const std::string staging = staging_prefix(target);
  const std::string old = old_prefix(target);
  for (fs::directory_iterator it(target.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    for (const std::string& prefix : {staging, old}) {
      if (name.rfind(prefix, 0) != 0 || !process_gone(name.substr(prefix.size()))) continue;
      // Only a folder this program made: one holding the result marker, or an empty one (killed
      // between its mkdir and the marker).
      std::error_code rm;
      if (it->is_directory(rm) && !it->is_symlink(rm) &&
          (holds_marker(it->path(), kResultMarker) || fs::is_empty(it->path(), rm))) {
        remove_marked_tree(it->path(), rm);
      }
    }
  }
}

void check_replaceable(const std::string& shown, const fs::path& target) {
  check_clear_of_inputs("--out", shown, target);
  check_owned_or_new("--out", shown, target, kResultMarker);
}

/// Creates the parent of `target`; returns the first folder created (empty if
/// the parent existed).
fs::path create_parent(const std::string& shown, const fs::path& target) {
  const fs::path parent = target.parent_path();
  std::error_code ec;
  fs::path first_missing;
  for (fs::path p = parent; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    first_missing = p;
    if (p == p.parent_path()) break;
  }
  fs::create_directories(parent, ec);
  if (ec) throw UsageError("--out '" + shown + "' cannot be created: " + ec.message());
  return first_missing;
}

void remove_created_parents(const Transaction& t) {
  if (t.created_root.empty()) return;
  std::error_code ec;
  for (fs::path p = t.target.parent_path(); !p.empty(); p = p.parent_path()) {
    if (!fs::remove(p, ec) || ec) return;  // not empty (someone else's files): keep it
    if (p == t.created_root) return;
  }
}

void fsync_folder(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

void release(const Transaction& t) { g_in_use[t.slot] = 0; }

/// Swaps `t.staging` in place of `t.target`. Returns where the previous
/// result now is (empty when there was none). Throws io::UsageError.
fs::path swap_in(const Transaction& t) {
  const SignalBlock block;
  if (::renameat2(AT_FDCWD, t.staging.c_str(), AT_FDCWD, t.target.c_str(), RENAME_NOREPLACE) == 0) return {};
  int err = errno;
  if (err == EEXIST) {
    if (::renameat2(AT_FDCWD, t.staging.c_str(), AT_FDCWD, t.target.c_str(), RENAME_EXCHANGE) == 0) return t.staging;
    err = errno;
  }
  if (err != EINVAL && err != ENOSYS && err != ENOTSUP) {
    throw UsageError("--out '" + t.target.string() + "': cannot put the new result in place: " + io::errno_text(err));
  }
  // A file system without renameat2 flags: set the previous result aside, then rename.
  const fs::path old = t.target.parent_path() / (old_prefix(t.target) + std::to_string(::getpid()));
  publish(t.slot, old);  // the handler now removes what was set aside if the rename below cannot run
  const bool had_old = ::rename(t.target.c_str(), old.c_str()) == 0;
  if (::rename(t.staging.c_str(), t.target.c_str()) != 0) {
    err = errno;
    if (had_old) ::rename(old.c_str(), t.target.c_str());
    publish(t.slot, t.staging);
    throw UsageError("--out '" + t.target.string() + "': cannot put the new result in place: " + io::errno_text(err));
  }
  return had_old ? old : fs::path{};
}

}  // namespace

fs::path output_target(const fs::path& given) {
  const std::string shown = given.string();
  if (shown.empty()) throw UsageError("--out: expected a folder, got an empty value");
  const fs::path t = resolve_path("--out", given);
  if (t == t.root_path() || t.filename().empty()) throw UsageError("--out '" + shown + "': not a folder to replace");
  return t;
}

void check_output_folder(const fs::path& given) { check_replaceable(given.string(), output_target(given)); }

fs::path begin_output(const fs::path& given) {
  const std::string shown = given.string();
  const fs::path target = output_target(given);
  check_replaceable(shown, target);
  for (const Transaction& other : registry().open) {
    check_clear_of_output("--out", shown, target, "--out", other.shown.string(), other.target);
  }
  Registry& reg = registry();
  std::size_t slot = kMaxOpen;
  for (std::size_t i = 0; i < kMaxOpen; ++i) {
    if (g_in_use[i] == 0) {
      slot = i;
      break;
    }
  }
  if (slot == kMaxOpen || target.string().size() + 32 >= kMaxPath) {
    throw UsageError("--out '" + shown + "': too many output folders or too long a path");
  }
  Transaction t;
  t.shown = given;
  t.target = target;
  t.slot = slot;
  t.created_root = create_parent(shown, target);
  remove_stale_staging(target);
  t.staging = target.parent_path() / (staging_prefix(target) + std::to_string(::getpid()));
  std::error_code ec;
  fs::remove_all(t.staging, ec);
  install_handlers_once();
  publish(slot, t.staging);
  if (::mkdir(t.staging.c_str(), 0777) != 0) {
    const int err = errno;
    release(t);
    remove_created_parents(t);
    throw UsageError("--out '" + shown + "' is not writable: " + io::errno_text(err));
  }
  reg.open.push_back(t);
  write_marker("--out", t.staging, kResultMarker);
  return t.staging;
}

void commit_outputs() {
  Registry& reg = registry();
  if (reg.open.empty()) return;
  // From the first swap on, the new result is in place: a cleanup signal can no
  // longer give the old one back, so it is held for the rest of the run (which
  // then ends normally with the new result) instead of ending it with a result
  // the signal's handler claims to have undone.
  sigset_t cleanup;
  sigemptyset(&cleanup);
  for (const int s : kCleanupSignals) sigaddset(&cleanup, s);
  ::pthread_sigmask(SIG_BLOCK, &cleanup, nullptr);
  while (!reg.open.empty()) {
    const Transaction t = reg.open.front();
    fsync_folder(t.staging);
    fs::path previous;
    try {
      previous = swap_in(t);
    } catch (...) {
      abandon_outputs();
      throw;
    }
    reg.open.erase(reg.open.begin());
    reg.committed.push_back(t);
    fsync_folder(t.target.parent_path());
    if (!previous.empty()) {
      publish(t.slot, previous);
      std::error_code ec;
      remove_marked_tree(previous, ec);
    }
    release(t);
  }
}

void abandon_outputs() noexcept {
  Registry& reg = registry();
  for (const Transaction& t : reg.open) {
    std::error_code ec;
    remove_marked_tree(t.staging, ec);
    release(t);
    remove_created_parents(t);
  }
  reg.open.clear();
}

namespace {
std::string shown_folder(const Transaction& t) {
  std::string shown = t.shown.string();
  while (shown.size() > 1 && shown.back() == '/') shown.pop_back();
  return shown;
}
}  // namespace

fs::path shown_path(const fs::path& path) {
  const Registry& reg = registry();
  std::vector<Transaction> all = reg.open;
  all.insert(all.end(), reg.committed.begin(), reg.committed.end());
  for (const Transaction& t : all) {
    const std::string s = path.string();
    const std::string staging = t.staging.string();
    if (s.rfind(staging, 0) == 0 && (s.size() == staging.size() || s[staging.size()] == '/')) {
      return fs::path(shown_folder(t) + s.substr(staging.size()));
    }
  }
  return path;
}

std::string shown_text(std::string text) {
  const Registry& reg = registry();
  std::vector<Transaction> all = reg.open;
  all.insert(all.end(), reg.committed.begin(), reg.committed.end());
  for (const Transaction& t : all) {
    const std::string staging = t.staging.string();
    const std::string shown = shown_folder(t);
    for (std::size_t at = text.find(staging); at != std::string::npos; at = text.find(staging, at + shown.size())) {
      text.replace(at, staging.size(), shown);
    }
  }
  return text;
}

}  // namespace mrd::report
