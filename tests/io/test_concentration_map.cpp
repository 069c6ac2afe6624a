// The concentration-map CSV goes through the shared table reader (it had its own: hexadecimal
// numbers and trailing commas were accepted, a byte-order mark was shown as an invisible
// character in its error, 1e-400 read as 0): the same rules as every table, file:line errors.

#include <gtest/gtest.h>

#include "core/params/concentration_map.h"
#include "support/errors.h"

namespace nx {
namespace {

std::string errorOf(const std::string& text) {
  return test::errorMessage([&] { (void)parseConcentrationCsv(text, "c.csv"); });
}

TEST(ConcentrationMap, CsvIsReadByTheSharedTableReader) {
  const ConcentrationMap m = parseConcentrationCsv("0.5, 1\n0,0.25\n", "c.csv");
  EXPECT_EQ(m.width, 2);
  EXPECT_EQ(m.height, 2);
  EXPECT_EQ(m.values, (std::vector<float>{0.5f, 1, 0, 0.25f}));
  // A spreadsheet's byte-order mark is skipped: the same map.
  EXPECT_EQ(parseConcentrationCsv("\xEF\xBB\xBF"
                                  "0.5, 1\n0,0.25\n",
                                  "c.csv")
                .values,
            m.values);
  EXPECT_EQ(errorOf("0.5,0x1p-1\n"),
            "c.csv:1: expected a number, found '0x1p-1' (not a decimal number)");
  EXPECT_EQ(errorOf("0.5,0.5,\n0.5,0.5,\n"), "c.csv:1: expected a number, found ''");
  EXPECT_EQ(errorOf("0.5,1e-400\n"),
            "c.csv:1: expected a number, found '1e-400' (below the smallest non-zero number a "
            "double holds, 4.9e-324: write 0)");
  EXPECT_EQ(errorOf("0.5,0.5\n0.5\n"), "c.csv:2: expected 2 values in every row (as the first), "
                                       "found 1");
  EXPECT_EQ(errorOf("0.5,1.5\n"), "c.csv:1: expected concentrations in [0, 1] (shares of the "
                                  "dye's peak absorptance), found 1.5");
  EXPECT_EQ(errorOf(""), "c.csv: expected rows of numbers, found an empty file");
}

} // namespace
} // namespace nx
