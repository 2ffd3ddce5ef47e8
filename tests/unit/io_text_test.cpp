// Text helpers of the host readers: excerpts for one-line error messages,
// trimming and splitting, case folding, number formatting.

#include <gtest/gtest.h>

#include <string>

#include "host_sim/io/text.hpp"
#include "host_sim/io/usage_error.hpp"

namespace mrd::io {
namespace {

TEST(Excerpt, ReplacesControlAndNonAsciiBytesAndCutsLongText) {
  EXPECT_EQ(excerpt("a\tb\x01" "c\xC3\xA9", 60), "a?b?c??");
  EXPECT_EQ(excerpt(std::string(45, 'x'), 40), std::string(40, 'x') + "...");
  EXPECT_EQ(excerpt(std::string(40, 'x'), 40), std::string(40, 'x'));
  EXPECT_EQ(excerpt("", 10), "");
}

TEST(FormatNumber, UsesThePrintfFormat) {
  EXPECT_EQ(format_number("%.9g", 0.1), "0.1");
  EXPECT_EQ(format_number("%.6g", 1234567.0), "1.23457e+06");
  EXPECT_EQ(format_number("%.2f %%", 12.345), "12.35 %");
}

TEST(Trim, RemovesSpacesTabsAndLineBreaksAtBothEnds) {
  EXPECT_EQ(trim(" \t a b \r\n"), "a b");
  EXPECT_EQ(trim("   "), "");
  EXPECT_EQ(trim(""), "");
}

TEST(SplitCommas, TrimsEveryField) {
  const auto f = split_commas(" a , b,,c ");
  ASSERT_EQ(f.size(), 4u);
  EXPECT_EQ(f[0], "a");
  EXPECT_EQ(f[1], "b");
  EXPECT_EQ(f[2], "");
  EXPECT_EQ(f[3], "c");
  EXPECT_EQ(split_commas("").size(), 1u);
}

TEST(SplitWords, SplitsOnAnyWhitespace) {
  const auto w = split_words("  1.0\t-2E-3   x \r");
  ASSERT_EQ(w.size(), 3u);
  EXPECT_EQ(w[0], "1.0");
  EXPECT_EQ(w[1], "-2E-3");
  EXPECT_EQ(w[2], "x");
  EXPECT_TRUE(split_words(" \t ").empty());
}

TEST(Case, FoldsAsciiOnly) {
  EXPECT_EQ(to_upper("aT2.csv"), "AT2.CSV");
  EXPECT_EQ(to_lower("Force_kN"), "force_kn");
}

TEST(StripBom, RemovesOnlyALeadingByteOrderMark) {
  EXPECT_EQ(strip_bom("\xEF\xBB\xBFtime_s"), "time_s");
  EXPECT_EQ(strip_bom("time_s\xEF\xBB\xBF"), "time_s\xEF\xBB\xBF");
}

TEST(Labels, NameTheFileAndLine) {
  EXPECT_EQ(file_label("dir/a.csv"), "dir/a.csv");
  EXPECT_EQ(line_prefix("a.csv", 12), "a.csv:12: ");
}

TEST(UsageError, IsARuntimeErrorWithItsMessage) {
  try {
    throw UsageError("--out: bad");
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "--out: bad");
  }
}

}  // namespace
}  // namespace mrd::io
