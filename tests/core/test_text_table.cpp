#include <gtest/gtest.h>

#include "core/error.h"
#include "core/text_table.h"
#include "support/errors.h"

namespace nx {
namespace {

std::string errorOf(const std::string& text) {
  return test::errorMessage([&] { parseNumberTable(text, "t.csv", true); });
}

TEST(TextTable, ParsesHeaderCommentsAndSeparators) {
  const auto t =
      parseNumberTable("# note\nnm,value\n400, 0.5\n\n410;0.25\n420\t1e-1\n430 7\n", "t.csv", true);
  ASSERT_EQ(t.header.size(), 2u);
  EXPECT_EQ(t.header[1], "value");
  ASSERT_EQ(t.rows.size(), 4u);
  EXPECT_EQ(t.rows[0].line, 3);
  EXPECT_DOUBLE_EQ(t.rows[0].values[1], 0.5);
  EXPECT_DOUBLE_EQ(t.rows[2].values[1], 0.1);
  EXPECT_EQ(t.rows[3].line, 7);
  EXPECT_DOUBLE_EQ(t.rows[3].values[1], 7.0);
}

TEST(TextTable, ErrorsNameFileLineExpectedAndFound) {
  EXPECT_EQ(errorOf("400,0.5\n410,abc\n"), "t.csv:2: expected a number, found 'abc'");
  EXPECT_EQ(errorOf("400,,0.5\n"), "t.csv:1: expected a number, found ''");
  EXPECT_EQ(errorOf("400,nan\n"), "t.csv:1: expected a number, found 'nan' (not a finite value)");
  EXPECT_EQ(errorOf("400,1e999\n"),
            "t.csv:1: expected a number, found '1e999' (not a finite value)");
  EXPECT_EQ(errorOf("# only a comment\n"), "t.csv:1: expected rows of numbers, found none");
  EXPECT_EQ(errorOf(""), "t.csv: expected rows of numbers, found an empty file");
}

// A UTF-8 byte-order mark is skipped (it turned the first row into a header, which was then
// lost); UTF-16 is refused whole, not cut at its first NUL byte.
TEST(TextTable, ByteOrderMarksAndUtf16) {
  const auto t = parseNumberTable("\xEF\xBB\xBF"
                                  "400,0.5\n500,0.25\n",
                                  "t.csv", true);
  EXPECT_TRUE(t.header.empty());
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_DOUBLE_EQ(t.rows[0].values[0], 400.0);
  const std::string utf16("\xFF\xFE"
                          "4\0"
                          "0\0"
                          "0\0",
                          8);
  EXPECT_EQ(errorOf(utf16),
            "t.csv: expected UTF-8 or ASCII text, found UTF-16 (save the table as UTF-8)");
  EXPECT_EQ(errorOf(std::string("400,0.5\n4\0"
                                "10,1\n",
                                14)),
            "t.csv:2: expected text, found a NUL byte (a binary or UTF-16 file?)");
}

TEST(TextTable, UnreadableFile) {
  try {
    readNumberTable("/nonexistent/dir/x.csv", true);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/dir/x.csv: cannot open the table file");
  }
}

// Hexadecimal floats are not numbers of a scene or a table (strtod reads "0x1p3" as 8).
TEST(TextTable, HexadecimalIsNotANumber) {
  EXPECT_EQ(test::errorMessage([] { parseNumber("0x1p3", "t.scn:3", "a radius"); }),
            "t.scn:3: expected a radius, found '0x1p3' (not a decimal number)");
  EXPECT_EQ(errorOf("400,0X1\n"), "t.csv:1: expected a number, found '0X1' (not a decimal number)");
}

TEST(TextTable, ParseNumber) {
  EXPECT_DOUBLE_EQ(parseNumber(" 2.5 ", "w", "a radius"), 2.5);
  EXPECT_THROW(parseNumber("2.5x", "w", "a radius"), Error);
  EXPECT_THROW(parseNumber("", "w", "a radius"), Error);
  EXPECT_THROW(parseNumber("inf", "w", "a radius"), Error);
  // Below the smallest double, a non-zero number would read as 0: refused; subnormal numbers
  // and zero in any spelling are kept.
  EXPECT_EQ(errorOf("400,1e-400\n"),
            "t.csv:1: expected a number, found '1e-400' (below the smallest non-zero number a "
            "double holds, 4.9e-324: write 0)");
  EXPECT_EQ(parseNumber("1e-310", "w", "a number"), 1e-310);
  EXPECT_EQ(parseNumber("0e-400", "w", "a number"), 0.0);
  EXPECT_EQ(parseNumber("-0.0", "w", "a number"), 0.0);
}

// A table's cells are counted before any is stored, with what its reader keeps per cell: one
// beyond what the process may use is refused with figures, naming the file.
TEST(TextTable, CellsAreCountedAgainstMemoryBeforeStoring) {
  std::string text = "nm,a,b\n";
  for (int i = 0; i < 1000; ++i) text += std::to_string(400 + i) + ",0.5,0.25\n";
  EXPECT_EQ(parseNumberTable(text, "t.csv", true).rows.size(), 1000u);
  const std::string m = test::errorMessage([&] { parseNumberTable(text, "t.csv", true, 1e15); });
  EXPECT_EQ(m.substr(0, m.find(" (needs")),
            "t.csv: expected a table whose buffers fit in memory, found 3003 values");
}

} // namespace
} // namespace nx
