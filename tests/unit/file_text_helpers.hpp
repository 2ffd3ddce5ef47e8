#pragma once
/// What the tests of the TOML files users write (damper, fluid, drive) share:
/// a file's text, the text with one edit, the line an edit is on, and the
/// one-line error a parser gives.

#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "host_sim/io/usage_error.hpp"

namespace mrd::test {

/// The text of the file at `p`.
inline std::string file_text(const std::filesystem::path& p) {
  std::ifstream f(p);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

/// `text` with `from` replaced by `to` (once; the test fails when absent).
inline std::string edited(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// 1-based line of the first line of `text` that starts with `start`.
inline int line_of(const std::string& text, const std::string& start) {
  int line = 1;
  for (std::size_t pos = 0; pos < text.size(); ++line) {
    if (text.compare(pos, start.size(), start) == 0) return line;
    pos = text.find('\n', pos);
    if (pos == std::string::npos) break;
    ++pos;
  }
  return -1;
}

/// The io::UsageError `parse(text, origin)` throws (empty when it parses).
template <class Parse>
std::string parse_error_of(Parse parse, const std::string& text, const std::string& origin) {
  try {
    (void)parse(text, origin);
  } catch (const io::UsageError& e) {
    return e.what();
  }
  return {};
}

/// One bad file and what its refusal must say.
struct Refusal {
  const char* kind;
  std::string text;
  std::string at;  ///< the start of the line the message names
  std::string field, problem;
};

/// Each case's error (`error_of`) is one line "ORIGIN:LINE: field: ..." with
/// LINE the line its text has `at` on, and contains `problem`.
template <class ErrorOf>
void expect_refusals(const std::vector<Refusal>& cases, ErrorOf error_of, const std::string& origin) {
  for (const Refusal& c : cases) {
    const std::string e = error_of(c.text);
    const int line = line_of(c.text, c.at);
    ASSERT_GT(line, 0) << c.kind;
    EXPECT_EQ(e.rfind(origin + ":" + std::to_string(line) + ": " + (c.field.empty() ? "" : c.field + ": "), 0), 0u)
        << c.kind << " -> " << e;
    EXPECT_NE(e.find(c.problem), std::string::npos) << c.kind << " -> " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << c.kind << " -> " << e;
  }
}

}  // namespace mrd::test
