#pragma once
/// Output folders as transactions: a run writes into a staging folder beside
/// its target (`.<name>.staging-<pid>` in the same parent, so on the same file
/// system) and the staging folder replaces the target as a whole only when
/// everything is written. A reader of the target sees the previous result or
/// the new one, never a mix, and no file of the previous result survives into
/// the new one.
///
/// - commit: the staging folder and the target swap names in one
///   renameat2(RENAME_EXCHANGE) (a plain rename when there was no target),
///   then the previous result, now under the staging name, is removed. From
///   the commit on, SIGINT, SIGTERM, SIGHUP and SIGQUIT are held: the run ends
///   normally with the new result.
/// - an error (an exception reaching `mrd`'s main), a normal exit without a
///   commit, or SIGINT, SIGTERM, SIGHUP or SIGQUIT before the commit: the
///   staging folder is removed and the target is left exactly as it was;
///   folders created to hold the target are removed again.
/// - SIGKILL cannot be caught: it can leave a staging folder (never a
///   half-written target). The next run into the same parent removes staging
///   folders of processes that no longer run.

#include <filesystem>
#include <string>

namespace mrd::report {

/// The folder `--out` names, resolved (report::resolve_path): absolute,
/// links followed, no trailing separator. Throws io::UsageError for an empty
/// value or the root folder.
std::filesystem::path output_target(const std::filesystem::path& given);

/// The checks begin_output makes before it creates anything (the folder is
/// absent, empty or an mrd result, and clear of the declared inputs), for a
/// command to refuse a bad --out before any work. Throws io::UsageError.
void check_output_folder(const std::filesystem::path& given);

/// Starts a transaction on the output folder `target` and returns the
/// staging folder to write into, with the result marker
/// (report::kResultMarker) already in it. Checks first, and throws
/// io::UsageError naming `--out` when: `target` exists and is not a folder;
/// `target` is a folder that holds files but no result marker (not made by
/// `mrd`: it is never replaced); `target` is, contains or lies inside one of
/// the command's declared inputs or another open output; the parent cannot be
/// created or written. Removes stale staging folders (holding the marker, or
/// empty) of dead processes beside `target`.
std::filesystem::path begin_output(const std::filesystem::path& target);

/// Swaps every open transaction's staging folder in place of its target and
/// removes the previous results. Throws io::UsageError when a swap fails
/// (the target is then unchanged and the staging folder removed).
void commit_outputs();

/// Removes every open transaction's staging folder and the parent folders it
/// created; targets are untouched. Safe to call more than once.
void abandon_outputs() noexcept;

/// `path` with a staging folder (open or committed) replaced by its target as
/// the user named it, for messages:
/// what the user named, not where the run writes before the commit.
std::filesystem::path shown_path(const std::filesystem::path& path);

/// `text` with every open staging folder's path replaced by its target as the
/// user named it (for messages that quote paths).
std::string shown_text(std::string text);

}  // namespace mrd::report
