#pragma once
/// Text helpers shared by the host readers and reports: one-line excerpts of
/// user text for error messages, whitespace trimming and splitting, case
/// folding, and printf-style number formatting.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace mrd::io {

/// Up to `max_chars` characters of user text with control characters and
/// non-ASCII bytes replaced by '?' and "..." appended when cut, so that an
/// error message quoting it stays on one printable line.
[[nodiscard]] std::string excerpt(std::string_view text, std::size_t max_chars);

/// `value` formatted by `printf_format`, a printf format with exactly one
/// double conversion (e.g. "%.9g", "%.2f %%"). Results longer than 63
/// characters are cut.
[[nodiscard]] std::string format_number(const char* printf_format, double value);

/// Space, tab, CR, LF, VT or FF.
[[nodiscard]] bool is_space(char c) noexcept;

/// `s` without leading and trailing is_space characters.
[[nodiscard]] std::string_view trim(std::string_view s) noexcept;

/// The fields between commas, each trimmed; one field for a line without a
/// comma, an empty field for an empty line.
[[nodiscard]] std::vector<std::string_view> split_commas(std::string_view line);

/// The runs of non-space characters.
[[nodiscard]] std::vector<std::string_view> split_words(std::string_view line);

/// ASCII upper / lower case copies.
[[nodiscard]] std::string to_upper(std::string_view s);
[[nodiscard]] std::string to_lower(std::string_view s);

/// `text` without a leading UTF-8 byte-order mark.
[[nodiscard]] std::string_view strip_bom(std::string_view text) noexcept;

/// How error messages name a file: its path as given.
[[nodiscard]] std::string file_label(const std::filesystem::path& path);

/// The whole content of the regular file `path`, read under the reader policy
/// (posix::read_regular_file, firmware/platform/linux/regular_file.hpp: a
/// descriptor that cannot block; FIFOs, devices and folders are refused before
/// any read). Throws io::UsageError "<file>: <problem>" for a missing file, one
/// that is not a regular file, one larger than `max_bytes` (the limit is
/// stated), or a read error.
[[nodiscard]] std::string read_regular_file(const std::filesystem::path& path, std::size_t max_bytes);

/// Checks that `path` names a regular file of at most `max_bytes` (the same
/// refusals as read_regular_file, without reading it), for readers that open
/// the file themselves.
void check_regular_file(const std::filesystem::path& path, std::size_t max_bytes);

/// The system's text for the errno value `err` (std::strerror).
[[nodiscard]] std::string errno_text(int err);

/// "<file>:<line_no>: ", the start of a message about one line of a file.
[[nodiscard]] std::string line_prefix(const std::string& file, std::size_t line_no);

}  // namespace mrd::io
