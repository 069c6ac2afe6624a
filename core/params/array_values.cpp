#include "core/params/array_values.h"

#include <charconv>
#include <cmath>

#include "core/error.h"
#include "core/hash.h"
#include "core/number_text.h"

namespace nx {
namespace {

template <typename T>
uint64_t bytesDigest(const std::vector<T>& v, uint32_t columns) {
  return fnv1a64(std::string_view(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T)),
                 fnv1a64(std::to_string(columns)));
}

void checkCount(size_t count, uint32_t columns) {
  if (count == 0 || count % columns != 0)
    throw Error("expected rows of " + std::to_string(columns) + " numbers, found " +
                std::to_string(count) + " numbers");
}

bool separator(char c) {
  return c == ',' || c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

} // namespace

ArrayDesc realRows(std::vector<float> values, uint32_t columns) {
  checkCount(values.size(), columns);
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw Error("expected finite numbers, found " +
                  std::string(std::isnan(values[i]) ? "nan" : "inf") + " in row " +
                  std::to_string(i / columns));
  ArrayDesc a;
  a.columns = columns;
  a.digest = bytesDigest(values, columns);
  a.reals = std::make_shared<const std::vector<float>>(std::move(values));
  return a;
}

ArrayDesc indexRows(std::vector<uint32_t> values, uint32_t columns) {
  checkCount(values.size(), columns);
  ArrayDesc a;
  a.columns = columns;
  a.digest = bytesDigest(values, columns) ^ 0x9e3779b97f4a7c15ull; // indices differ from reals
  a.indices = std::make_shared<const std::vector<uint32_t>>(std::move(values));
  return a;
}

ArrayDesc arrayFromText(std::string_view text, bool indices, uint32_t columns) {
  std::vector<float> reals;
  std::vector<uint32_t> whole;
  const char* p = text.data();
  const char* end = p + text.size();
  // Rows separated by commas must each hold `columns` numbers (a (N, 2) array given for
  // (N, 3) rows is refused, not read as other rows); without commas the numbers run on.
  const bool rowsMarked = text.find(',') != std::string_view::npos;
  size_t inRow = 0, row = 0;
  auto endRow = [&] {
    if (rowsMarked && inRow != columns)
      throw Error("expected rows of " + std::to_string(columns) +
                  " numbers separated by commas, found " + std::to_string(inRow) +
                  " numbers in row " + std::to_string(row));
    inRow = 0, ++row;
  };
  while (true) {
    while (p < end && separator(*p)) {
      if (*p == ',') endRow();
      ++p;
    }
    if (p == end) {
      if (inRow) endRow();
      break;
    }
    ++inRow;
    const char* q = p;
    while (q < end && !separator(*q)) ++q;
    const std::string_view token(p, static_cast<size_t>(q - p));
    const size_t index = indices ? whole.size() : reals.size();
    const std::string where = " (number " + std::to_string(index + 1) + ")";
    if (indices) {
      uint32_t v = 0;
      const auto r = std::from_chars(p, q, v);
      if (r.ec != std::errc() || r.ptr != q)
        throw Error("expected whole numbers in [0, 2^32), found '" + std::string(token) + "'" +
                    where);
      whole.push_back(v);
    } else {
      float v = 0;
      const char* start = p < q && *p == '+' ? p + 1 : p;
      const auto r = std::from_chars(start, q, v);
      if (r.ec != std::errc() || r.ptr != q || !std::isfinite(v))
        throw Error("expected finite numbers, found '" + std::string(token) + "'" + where);
      reals.push_back(v);
    }
    p = q;
  }
  return indices ? indexRows(std::move(whole), columns) : realRows(std::move(reals), columns);
}

std::string arrayText(const ArrayDesc& a) {
  std::string out;
  const size_t n = a.reals ? a.reals->size() : a.indices ? a.indices->size() : 0;
  out.reserve(n * 10);
  for (size_t i = 0; i < n; ++i) {
    if (i) out += i % a.columns == 0 ? ", " : " ";
    out += a.reals ? shortestText((*a.reals)[i]) : std::to_string((*a.indices)[i]);
  }
  return out;
}

} // namespace nx
