#pragma once
// The one exception type nxrender throws for bad input and failed I/O.

#include "core/number_text.h"
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace nx {

/// A user-facing error: its message is complete ("file:line: expected ..., found ...").
class Error : public std::runtime_error {
public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

/// The shortest decimal text that reads back as exactly v (at most 17 significant digits):
/// numbers stored in files to be parsed again (bands, camera attributes).
inline std::string exactNumberText(double v) {
  std::string text;
  for (int digits = 6; digits <= 17; ++digits) {
    text = generalText(v, digits);
    if (strtodC(text.c_str()) == v) break;
  }
  return text;
}

/// A number as error messages show it: up to 7 significant digits, no trailing zeros.
inline std::string numberText(double v) {
  return generalText(v, 7);
}

/// "a, b or c": names listed in a message.
inline std::string listWithOr(const std::vector<std::string>& items) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i)
    out += (i == 0 ? "" : i + 1 == items.size() ? " or " : ", ") + items[i];
  return out;
}

} // namespace nx
