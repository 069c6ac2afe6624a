#include "core/params/concentration_map.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/hash.h"
#include "core/texel_grid.h"
#include "core/text_table.h"

namespace nx {

void ConcentrationMap::bilinear(float u, float v, size_t (&index)[4], float (&weight)[4]) const {
  const BilinearTexels b = bilinearTexels(u, v, width, height);
  for (int k = 0; k < 4; ++k) index[k] = b.texel[k], weight[k] = b.weight[k];
}

ConcentrationMap makeConcentrationMap(int width, int height, std::vector<float> values,
                                      const std::string& where) {
  if (width < 1 || height < 1 || values.size() != static_cast<size_t>(width) * height)
    throw Error(where + ": expected a concentration map of at least 1 x 1 values, found " +
                std::to_string(width) + " x " + std::to_string(height));
  for (size_t i = 0; i < values.size(); ++i)
    if (!(values[i] >= 0 && values[i] <= 1)) {
      std::ostringstream found;
      found << values[i];
      throw Error(where +
                  ": expected concentrations in [0, 1] (shares of the dye's peak "
                  "absorptance), found " +
                  found.str() + " at row " + std::to_string(i / static_cast<size_t>(width)) +
                  ", column " + std::to_string(i % static_cast<size_t>(width)));
    }
  ConcentrationMap m;
  m.width = width, m.height = height;
  m.digest = fnv1a64(
      std::string_view(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float)),
      fnv1a64(std::to_string(width) + "x" + std::to_string(height)));
  m.values = std::move(values);
  return m;
}

ConcentrationMap parseConcentrationCsv(const std::string& text, const std::string& source) {
  // The shared table reader: hexadecimal numbers, empty cells (a trailing comma), byte-order
  // marks and numbers beyond a double's range are refused or handled as in every table.
  const NumberTable t = parseNumberTable(text, source, false, sizeof(float));
  const size_t width = t.rows.front().values.size();
  std::vector<float> values;
  values.reserve(width * t.rows.size());
  for (const TableRow& row : t.rows) {
    const std::string where = source + ":" + std::to_string(row.line);
    if (row.values.size() != width)
      throw Error(where + ": expected " + std::to_string(width) +
                  " values in every row (as the first), found " +
                  std::to_string(row.values.size()));
    for (const double v : row.values) {
      if (!(v >= 0 && v <= 1))
        throw Error(where +
                    ": expected concentrations in [0, 1] (shares of the dye's peak "
                    "absorptance), found " +
                    numberText(v));
      values.push_back(static_cast<float>(v));
    }
  }
  return makeConcentrationMap(static_cast<int>(width), static_cast<int>(t.rows.size()),
                              std::move(values), source);
}

} // namespace nx
