#pragma once
/// The records of a folder (`--records DIR`), by one rule wherever a folder
/// of records is read:
///
/// * a name starting with '.' is skipped (hidden files, editors' and
///   file managers' leftovers), whatever it is;
/// * a name with a record extension (.csv or .at2, any case) is a record: it
///   must be a regular file (a link to one counts); a folder, FIFO, device,
///   socket or broken link of that name is an error naming it;
/// * any other name is not a record and is skipped.
///
/// The records come sorted by name, so a study's record order does not
/// depend on the file system.

#include <filesystem>
#include <string>
#include <vector>

namespace mrd::excitation {

/// The extensions a record file has, lower case.
inline constexpr const char* kRecordExtensions[] = {".csv", ".at2"};

/// True for a name with a record extension (any case).
bool has_record_extension(const std::filesystem::path& name);

/// The records of `dir` under the rule above, sorted. Throws io::UsageError
/// "<option>: ..." when `dir` is not a folder or cannot be listed, when an
/// entry with a record extension is not a regular file (naming it and what
/// it is), or when the folder holds no record.
std::vector<std::filesystem::path> record_files_in_folder(const std::string& option, const std::filesystem::path& dir);

}  // namespace mrd::excitation
