#pragma once
// Numbers to text and back, the same in every locale: std::to_chars and std::from_chars, never
// printf, strtod or sscanf, whose decimal point follows the process's C locale (a Python host
// that sets a decimal-comma locale made every scene unreadable, and channel names "500,000000").

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

namespace nx {

/// v as the shortest text that reads back to it; a whole number below 2^53 as an integer
/// (std::to_chars alone writes 100000 as "1e+05", which an integer field such as a seed, a sample
/// count or a face's vertex index refuses).
template <class F>
inline std::string shortestText(F v) {
  char b[64];
  if (std::isfinite(v) && v == std::trunc(v) && std::abs(v) < F(9007199254740992.0)) {
    const auto r = std::to_chars(b, b + sizeof b, static_cast<int64_t>(v));
    return std::string(b, r.ptr);
  }
  const auto r = std::to_chars(b, b + sizeof b, v);
  return std::string(b, r.ptr);
}

/// printf's "%.<decimals>f" in the C locale.
inline std::string fixedText(double v, int decimals) {
  char b[400];
  const auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::fixed, decimals);
  return r.ec == std::errc() ? std::string(b, r.ptr) : std::string("inf");
}

/// printf's "%.<digits>g" in the C locale.
inline std::string generalText(double v, int digits) {
  char b[64];
  const auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::general, digits);
  return std::string(b, r.ptr);
}

/// std::strtod in the C locale: leading white space and a sign, then a decimal number (also inf
/// and nan), or a hexadecimal one after 0x; `end` (if given) past what was read (`s` when nothing
/// was). Out of range: +-HUGE_VAL or 0 as strtod gives, with `*outOfRange` set.
inline double strtodC(const char* s, const char** end = nullptr, bool* outOfRange = nullptr) {
  if (outOfRange) *outOfRange = false;
  const char* p = s;
  while (std::isspace(static_cast<unsigned char>(*p))) ++p;
  bool negative = false;
  if (*p == '+' || *p == '-') negative = *p++ == '-';
  if (*p == '+' || *p == '-') { // a second sign: no number
    if (end) *end = s;
    return 0;
  }
  const char* last = p + std::strlen(p);
  double v = 0;
  std::from_chars_result r{};
  if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X') && p[2] != '+' && p[2] != '-') {
    r = std::from_chars(p + 2, last, v, std::chars_format::hex);
    if (r.ec == std::errc::invalid_argument) r = std::from_chars(p, p + 1, v); // just "0"
  } else {
    r = std::from_chars(p, last, v);
  }
  if (r.ec == std::errc::invalid_argument) {
    if (end) *end = s;
    return 0;
  }
  if (r.ec == std::errc::result_out_of_range) {
    if (outOfRange) *outOfRange = true;
    // Too small when the exponent is negative, else too large.
    const char* e = p;
    while (e < r.ptr && *e != 'e' && *e != 'E' && *e != 'p' && *e != 'P') ++e;
    v = e < r.ptr && e[1] == '-' ? 0.0 : HUGE_VAL;
  }
  if (end) *end = r.ptr;
  return negative ? -v : v;
}

} // namespace nx
