#include "core/text_table.h"

#include "core/number_text.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>

#include "core/error.h"
#include "core/file_text.h"
#include "core/memory.h"

namespace nx {
namespace {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

// Cells split on commas, semicolons or tabs when the line has any (empty cells kept, so
// that "1,,2" is reported), otherwise on runs of spaces.
std::vector<std::string> splitCells(const std::string& rawLine) {
  const std::string line = trim(rawLine);
  std::vector<std::string> cells;
  if (line.empty()) return cells;
  if (line.find_first_of(",;\t") != std::string::npos) {
    std::string cell;
    for (char c : line) {
      if (c == ',' || c == ';' || c == '\t') {
        cells.push_back(trim(cell));
        cell.clear();
      } else {
        cell += c;
      }
    }
    cells.push_back(trim(cell));
    return cells;
  }
  std::istringstream words(line);
  for (std::string w; words >> w;) cells.push_back(w);
  return cells;
}

bool looksNumeric(const std::string& cell) {
  const char* end = nullptr;
  strtodC(cell.c_str(), &end);
  return end != cell.c_str() && *end == '\0';
}

} // namespace

double parseNumber(const std::string& text, const std::string& where, const std::string& what) {
  // Decimal numbers only: strtod also reads hexadecimal ("0x1p3" = 8), which no scene or
  // table of spectra means.
  const size_t digits = text.find_first_not_of(" \t\r\n+-");
  const std::string prefix = digits == std::string::npos ? "" : text.substr(digits, 2);
  if (prefix == "0x" || prefix == "0X")
    throw Error(where + ": expected " + what + ", found '" + text + "' (not a decimal number)");
  const char* begin = text.c_str();
  while (*begin == ' ' || *begin == '\t' || *begin == '\n' || *begin == '\r') ++begin;
  const char* end = nullptr;
  bool outOfRange = false;
  const double value = strtodC(begin, &end, &outOfRange);
  const char* rest = end;
  while (*rest == ' ' || *rest == '\t' || *rest == '\n' || *rest == '\r') ++rest;
  if (end == begin || *rest != '\0')
    throw Error(where + ": expected " + what + ", found '" + text + "'");
  if (!std::isfinite(value) || (outOfRange && std::abs(value) > 1.0))
    throw Error(where + ": expected " + what + ", found '" + text + "' (not a finite value)");
  // A non-zero number below the smallest a double holds (1e-400) would read as 0: refused
  // rather than changed (subnormal values, down to 4.9e-324, are kept).
  if (outOfRange && value == 0)
    throw Error(where + ": expected " + what + ", found '" + text +
                "' (below the smallest non-zero number a double holds, 4.9e-324: write 0)");
  return value;
}

NumberTable parseNumberTable(const std::string& rawText, const std::string& source,
                             bool allowHeader, double bytesPerValue) {
  // The cells (runs of characters between separators) and lines, counted before any is
  // stored: their doubles, each row's vector and what the caller makes of them must fit.
  size_t cellCount = 0, lines = 1;
  bool inCell = false;
  for (const char c : rawText) {
    const bool separator = c == ',' || c == ';' || c == ' ' || c == '\t' || c == '\n' || c == '\r';
    cellCount += !separator && !inCell;
    inCell = !separator;
    lines += c == '\n';
  }
  const double bytes = static_cast<double>(cellCount) * (8.0 + bytesPerValue) +
                       static_cast<double>(lines) * 64.0 +
                       2.0 * static_cast<double>(rawText.size());
  if (bytes > 16.0 * (1 << 20))
    requireMemory(bytes, source, "a table", std::to_string(cellCount) + " values");
  NumberTable table;
  table.source = source;
  // A UTF-8 byte-order mark (spreadsheet exports) is skipped: it made the first row look like
  // a header. UTF-16 and other binary text is refused, whole, with what it is.
  const std::string_view bom = "\xEF\xBB\xBF";
  const std::string_view view(rawText);
  const std::string text(view.substr(view.substr(0, 3) == bom ? 3 : 0));
  if (text.size() >= 2 &&
      ((text[0] == '\xFF' && text[1] == '\xFE') || (text[0] == '\xFE' && text[1] == '\xFF')))
    throw Error(source + ": expected UTF-8 or ASCII text, found UTF-16 (save the table as UTF-8)");
  if (const size_t nul = text.find('\0'); nul != std::string::npos)
    throw Error(source + ":" +
                std::to_string(1 + std::count(text.begin(), text.begin() + nul, '\n')) +
                ": expected text, found a NUL byte (a binary or UTF-16 file?)");
  std::istringstream in(text);
  std::string line;
  int lineNumber = 0;
  bool first = true;
  while (std::getline(in, line)) {
    ++lineNumber;
    const auto cells = splitCells(line);
    if (cells.empty() || (!cells[0].empty() && cells[0][0] == '#')) continue;
    if (first && allowHeader && !looksNumeric(cells[0])) {
      table.header = cells;
      first = false;
      continue;
    }
    first = false;
    TableRow row;
    row.line = lineNumber;
    const std::string where = source + ":" + std::to_string(lineNumber);
    // A spreadsheet in a decimal-comma locale writes "400;0,5": split on both, that reads as
    // three numbers. Say what it is instead of a column-count error.
    if (line.find(';') != std::string::npos && line.find(',') != std::string::npos)
      throw Error(where + ": expected numbers with decimal points, found '" + trim(line) +
                  "' (semicolons and decimal commas, as a spreadsheet in a decimal-comma locale "
                  "writes; export with decimal points, e.g. 400,0.5 or 400;0.5)");
    for (const auto& cell : cells) row.values.push_back(parseNumber(cell, where, "a number"));
    table.rows.push_back(std::move(row));
  }
  if (lineNumber == 0) throw Error(source + ": expected rows of numbers, found an empty file");
  if (table.rows.empty())
    throw Error(source + ":" + std::to_string(lineNumber) +
                ": expected rows of numbers, found none");
  return table;
}

NumberTable readNumberTable(const std::string& path, bool allowHeader) {
  return parseNumberTable(readRegularFile(path, 64u << 20, "table file"), path, allowHeader);
}

} // namespace nx
