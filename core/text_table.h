#pragma once
// Reading small numeric tables (CSV or whitespace separated) with file:line errors.

#include <string>
#include <vector>

namespace nx {

/// One row of numbers and the line of the file it came from.
struct TableRow {
  int line = 0;
  std::vector<double> values;
};

/// A numeric table: optional header cells, then rows of numbers.
struct NumberTable {
  std::string source;              ///< file name used in error messages
  std::vector<std::string> header; ///< cells of a non-numeric first line, if any
  std::vector<TableRow> rows;
};

/// Parses table text. Cells are separated by commas, semicolons, tabs or spaces; blank lines
/// and lines starting with '#' are skipped; the first remaining line may be a header of
/// non-numeric cells when allowHeader is set. Throws nx::Error "source:line: ..." on a
/// malformed or non-finite cell, or when the table holds no rows. Before anything is stored,
/// its cells are counted and their memory (8 bytes each, plus `bytesPerValue` more that the
/// caller will hold per value) checked against what the process may use (core/memory.h), so a
/// large file is refused with figures instead of ending in std::bad_alloc.
NumberTable parseNumberTable(const std::string& text, const std::string& source, bool allowHeader,
                             double bytesPerValue = 0);

/// Reads and parses a table file (see parseNumberTable); an unreadable file is an nx::Error.
NumberTable readNumberTable(const std::string& path, bool allowHeader);

/// Parses one number; on failure throws nx::Error "where: expected <what>, found '<text>'".
double parseNumber(const std::string& text, const std::string& where, const std::string& what);

} // namespace nx
