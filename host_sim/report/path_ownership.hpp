#pragma once
/// What `mrd` may replace or remove: only what it made. Every folder it
/// replaces or removes carries a marker file of its own kind, and every output
/// path is checked against the command's inputs before any work:
///
/// - an `--out` folder is replaced as a whole only when it holds the result
///   marker (kResultMarker, written into every result) or is empty;
/// - a journal folder (`mrd fragility --journal`) is used and removed only when
///   it holds the journal marker (kJournalMarker) or is empty or absent, and its
///   removal takes only the journal's own files;
/// - an output (`--out`, a journal) that is, contains or lies inside one of the
///   command's inputs, or inside another output, is refused with
///   io::UsageError naming both paths.
///
/// Paths are compared resolved: absolute, symbolic links followed, `.` and
/// `..` folded and trailing separators dropped (resolve_path), so `D`, `D/`,
/// `./x/../D` and a link to D are one folder.

#include <filesystem>
#include <string>
#include <vector>

namespace mrd::report {

/// Marker file of a result folder and of a journal folder.
inline constexpr const char* kResultMarker = ".mrd-result";
inline constexpr const char* kJournalMarker = ".mrd-journal";

/// `given` absolute, its existing part's symbolic links resolved, `.` and
/// `..` folded, without a trailing separator. Throws io::UsageError naming
/// `option` when the path cannot be made absolute.
std::filesystem::path resolve_path(const std::string& option, const std::filesystem::path& given);

/// How the resolved path `a` lies against the resolved path `b`.
enum class Overlap { kNone, kSame, kContains, kInside };
Overlap overlap(const std::filesystem::path& a, const std::filesystem::path& b);

/// A path a command reads, with the option that named it.
struct InputPath {
  std::string option;
  std::filesystem::path shown;     ///< as the user gave it
  std::filesystem::path resolved;  ///< resolve_path of it
};

/// Declares the inputs of the running command (replacing earlier ones);
/// `mrd`'s main declares every option value that names an existing path.
void declare_inputs(std::vector<InputPath> inputs);
const std::vector<InputPath>& declared_inputs();

/// Throws io::UsageError "<option> '<shown>' <is|contains|lies inside> the
/// input '<input>' (<input option>): ..." when the resolved output `resolved`
/// overlaps a declared input.
void check_clear_of_inputs(const std::string& option, const std::string& shown, const std::filesystem::path& resolved);

/// Throws io::UsageError naming both when the outputs `a` and `b` (resolved)
/// overlap.
void check_clear_of_output(const std::string& option_a, const std::string& shown_a, const std::filesystem::path& a,
                           const std::string& option_b, const std::string& shown_b, const std::filesystem::path& b);

/// Checks that the folder `dir` (resolved) may be used and later removed as a
/// folder of the kind `marker`: absent, empty, or holding `marker`. Throws
/// io::UsageError naming `option` and `shown` otherwise ("exists and is not a
/// folder", "is a folder with other files and no <marker>").
void check_owned_or_new(const std::string& option, const std::string& shown, const std::filesystem::path& dir,
                        const char* marker);

/// Creates `dir` (and parents) if needed and writes `marker` in it, after
/// check_owned_or_new. Throws io::UsageError naming `option`.
void claim_folder(const std::string& option, const std::filesystem::path& dir, const char* marker);

/// Writes the marker file `marker` into the folder `dir`. Throws
/// io::UsageError naming `option` when it cannot.
void write_marker(const std::string& option, const std::filesystem::path& dir, const char* marker);

/// Whether the folder `dir` holds the marker `marker` as a regular file.
bool holds_marker(const std::filesystem::path& dir, const char* marker);

}  // namespace mrd::report
