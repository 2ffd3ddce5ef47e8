#include "host_sim/io/text.hpp"

#include <cctype>
#include <cstdio>
#include <cstring>

#include "firmware/platform/linux/regular_file.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::io {

std::string excerpt(std::string_view text, std::size_t max_chars) {
  std::string out;
  for (const char c : text.substr(0, max_chars)) {
    const auto u = static_cast<unsigned char>(c);
    out += (u < 0x20 || u >= 0x7f) ? '?' : c;
  }
  if (text.size() > max_chars) out += "...";
  return out;
}

std::string format_number(const char* printf_format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, printf_format, value);
  return buf;
}

bool is_space(char c) noexcept { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

std::string_view trim(std::string_view s) noexcept {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split_commas(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    if (comma == std::string_view::npos) {
      fields.push_back(trim(line.substr(start)));
      return fields;
    }
    fields.push_back(trim(line.substr(start, comma - start)));
    start = comma + 1;
  }
}

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

std::string to_upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

std::string to_lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string_view strip_bom(std::string_view text) noexcept {
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (text.substr(0, kBom.size()) == kBom) text.remove_prefix(kBom.size());
  return text;
}

std::string file_label(const std::filesystem::path& path) { return path.string(); }

std::string errno_text(int err) { return std::strerror(err); }

namespace {

/// "<file>: <problem>" as a usage error.
[[noreturn]] void refuse_file(const std::filesystem::path& path, const posix::FileCheck& check,
                              std::size_t max_bytes) {
  throw UsageError(file_label(path) + ": " + posix::problem_text(check, max_bytes));
}

}  // namespace

void check_regular_file(const std::filesystem::path& path, std::size_t max_bytes) {
  if (const posix::FileCheck c = posix::check_regular_file(path.c_str(), max_bytes); !c.ok()) {
    refuse_file(path, c, max_bytes);
  }
}

std::string read_regular_file(const std::filesystem::path& path, std::size_t max_bytes) {
  std::string data;
  if (const posix::FileCheck c = posix::read_regular_file(path.c_str(), max_bytes, data); !c.ok()) {
    refuse_file(path, c, max_bytes);
  }
  return data;
}

std::string line_prefix(const std::string& file, std::size_t line_no) {
  return file + ":" + std::to_string(line_no) + ": ";
}

}  // namespace mrd::io
