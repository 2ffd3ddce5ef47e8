#pragma once
/// The reader policy: every file the board programs and the host tools read
/// (board files, state files, records, baselines, hazard curves, journals)
/// is read here, and only as a regular file within a stated size. The file
/// is checked with stat() first (so that a device is never opened: opening
/// some has side effects), then opened with O_RDONLY | O_NONBLOCK | O_NOCTTY
/// | O_CLOEXEC, so that a FIFO put in its place meanwhile cannot block the
/// open, and checked again with fstat() on the descriptor: folders, FIFOs,
/// devices and sockets are refused before any read, and a file larger than
/// the limit (or growing past it while read) is refused too.
///
/// The readers return a FileCheck instead of throwing; problem_text() gives
/// the one wording every program uses: "<file>: " + problem_text(...). The
/// buffer reader allocates nothing and throws nothing (the state store's
/// load()); the string reader may throw only std::bad_alloc.
/// scripts/check-readers.sh refuses any other way of opening a file for
/// reading in common/, firmware/ and host_sim/ unless the line says which
/// check covers it.

#include <cstddef>
#include <cstdint>
#include <string>

namespace mrd::posix {

/// Why a file was not read (kNone: it was).
enum class FileProblem : std::uint8_t {
  kNone = 0,
  kMissing,     ///< no such file (ENOENT)
  kFolder,      ///< a folder
  kPipe,        ///< a FIFO
  kDevice,      ///< a character or block device
  kNotRegular,  ///< a socket or anything else that is not a regular file
  kTooLarge,    ///< larger than the caller's limit
  kStatFailed,  ///< stat()/fstat() failed other than ENOENT (errno in `err`)
  kOpenFailed,  ///< open() failed other than ENOENT (errno in `err`)
  kReadFailed,  ///< read() failed (errno in `err`)
};

/// The path exists but names a folder, a FIFO, a device or a socket.
constexpr bool is_non_regular(FileProblem p) noexcept {
  return p == FileProblem::kFolder || p == FileProblem::kPipe || p == FileProblem::kDevice ||
         p == FileProblem::kNotRegular;
}

/// The outcome of a check or a read.
struct FileCheck {
  FileProblem problem = FileProblem::kNone;
  int err = 0;                     ///< errno for kStatFailed, kOpenFailed, kReadFailed
  std::uintmax_t size_bytes = 0;   ///< kTooLarge: the size stat() gave ...
  bool grew = false;               ///< ... or true: it grew past the limit while read
  bool ok() const noexcept { return problem == FileProblem::kNone; }
};

/// Checks, without opening it, that `path` names a regular file of at most
/// `max_bytes` (for a reader that must hand the path to a library, e.g.
/// matio, after reading it here once).
FileCheck check_regular_file(const char* path, std::size_t max_bytes) noexcept;

/// Reads the whole of the regular file `path` into `buffer` (at most
/// `capacity` bytes: the limit); `size` is the number of bytes read.
FileCheck read_regular_file(const char* path, std::uint8_t* buffer, std::size_t capacity,
                            std::size_t& size) noexcept;

/// Reads the whole of the regular file `path` (at most `max_bytes`) into `text`.
FileCheck read_regular_file(const char* path, std::size_t max_bytes, std::string& text);

/// What went wrong, for a message "<file>: <problem>": "file not found",
/// "is a folder, expected a regular file", "is a pipe (FIFO), expected a
/// regular file", "is a device, expected a regular file", "is not a regular
/// file", "<n> bytes, larger than the limit of <limit>", "cannot read: …",
/// "cannot open: …", "read error: …". Empty for a check that is ok.
std::string problem_text(const FileCheck& check, std::size_t max_bytes);

/// For a path the program will both read and replace (a state file): what is
/// wrong with it when it exists and is not a regular file ("is a folder,
/// expected a regular file", …); empty when it is a regular file, does not
/// exist yet, or cannot be looked at (its reader reports that when it reads).
std::string non_regular_problem(const std::string& path);

}  // namespace mrd::posix
