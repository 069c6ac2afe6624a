#include "io/envi_header.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>

#include "core/error.h"
#include "core/file_text.h"
#include "core/text_table.h"

namespace nx {
namespace {

constexpr std::uintmax_t kMaxHeaderBytes = 16u << 20;

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// A whole number in [lo, hi] from `text`, or an error naming `where` and the field.
double wholeNumber(const std::string& text, const std::string& where, const std::string& key,
                   double lo, double hi, const std::string& note = "") {
  const double v = parseNumber(text, where, "a whole number for '" + key + "'");
  if (!(v == std::floor(v) && v >= lo && v <= hi))
    throw Error(where + ": expected '" + key + "' as a whole number from " + numberText(lo) +
                " to " + exactNumberText(hi) + note + ", found " + text);
  return v;
}

} // namespace

void checkEnviHeader(const std::string& headerPath, double dataBytes) {
  const std::string text = readRegularFile(headerPath, kMaxHeaderBytes, "ENVI header");
  // key -> (value, line)
  std::map<std::string, std::pair<std::string, int>> fields;
  size_t pos = 0;
  int line = 0;
  bool first = true;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string row = text.substr(pos, end - pos);
    pos = end + 1;
    ++line;
    const int rowLine = line;
    const std::string where = headerPath + ":" + std::to_string(rowLine);
    if (first) {
      if (trimmed(row).rfind("ENVI", 0) != 0)
        throw Error(where + ": expected an ENVI header starting with 'ENVI', found '" +
                    trimmed(row).substr(0, 40) + "'");
      first = false;
      continue;
    }
    if (trimmed(row).empty() || trimmed(row)[0] == ';') continue;
    const auto eq = row.find('=');
    if (eq == std::string::npos)
      throw Error(where + ": expected 'key = value', found '" + trimmed(row).substr(0, 40) + "'");
    std::string value = trimmed(row.substr(eq + 1));
    // A braced value runs to its closing brace, over lines.
    if (!value.empty() && value[0] == '{')
      while (value.find('}') == std::string::npos) {
        if (pos >= text.size())
          throw Error(where + ": expected the closing brace of '" + trimmed(row.substr(0, eq)) +
                      "', found the end of the header");
        end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        value += " " + trimmed(text.substr(pos, end - pos));
        pos = end + 1;
        ++line;
      }
    fields[lower(trimmed(row.substr(0, eq)))] = {value, rowLine};
  }
  if (first) throw Error(headerPath + ":1: expected an ENVI header, found an empty file");
  const auto at = [&](const std::string& key) {
    return headerPath + ":" + std::to_string(fields.at(key).second);
  };
  if (fields.count("interleave")) {
    const std::string v = lower(fields.at("interleave").first);
    if (v != "bsq" && v != "bil" && v != "bip")
      throw Error(at("interleave") + ": expected 'interleave' bsq, bil or bip, found '" +
                  fields.at("interleave").first + "'");
  }
  if (fields.count("byte order")) {
    const std::string& v = fields.at("byte order").first;
    if (v != "0" && v != "1")
      throw Error(at("byte order") +
                  ": expected 'byte order' 0 (little-endian) or 1 (big-endian), found '" + v + "'");
  }
  if (fields.count("data type")) {
    static const std::set<std::string> kTypes{"1", "2", "3", "4", "5", "12", "13", "14", "15"};
    const std::string& v = fields.at("data type").first;
    if (!kTypes.count(v))
      throw Error(at("data type") +
                  ": expected a real 'data type' (1 byte, 2 int16, 3 int32, 4 float32, 5 "
                  "float64, 12 uint16, 13 uint32, 14 int64, 15 uint64), found '" +
                  v + "'");
  }
  for (const char* key : {"samples", "lines", "bands"})
    if (fields.count(key)) wholeNumber(fields.at(key).first, at(key), key, 1, 2147483647.0);
  if (fields.count("header offset"))
    wholeNumber(fields.at("header offset").first, at("header offset"), "header offset", 0,
                dataBytes, " (the data file's size in bytes)");
}

} // namespace nx
