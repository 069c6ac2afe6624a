#include "io/concentration_map.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/hash.h"
#include "core/texel_grid.h"

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
  std::vector<float> values;
  int width = -1, height = 0, line = 0;
  std::istringstream in(text);
  std::string row;
  while (std::getline(in, row)) {
    ++line;
    if (!row.empty() && row.back() == '\r') row.pop_back();
    if (row.find_first_not_of(" \t") == std::string::npos) continue;
    int count = 0;
    std::istringstream cells(row);
    std::string cell;
    const std::string where = source + ":" + std::to_string(line);
    while (std::getline(cells, cell, ',')) {
      const size_t a = cell.find_first_not_of(" \t"), b = cell.find_last_not_of(" \t");
      const std::string t = a == std::string::npos ? "" : cell.substr(a, b - a + 1);
      char* end = nullptr;
      const double v = std::strtod(t.c_str(), &end);
      if (t.empty() || end != t.c_str() + t.size() || !std::isfinite(v))
        throw Error(where + ": expected a concentration (a number in [0, 1]), found '" + t + "'");
      if (!(v >= 0 && v <= 1))
        throw Error(where +
                    ": expected concentrations in [0, 1] (shares of the dye's peak "
                    "absorptance), found " +
                    t);
      values.push_back(static_cast<float>(v));
      ++count;
    }
    if (width >= 0 && count != width)
      throw Error(where + ": expected " + std::to_string(width) +
                  " values in every row (as the first), found " + std::to_string(count));
    width = count;
    ++height;
  }
  if (height == 0) throw Error(source + ": expected rows of concentrations, found none");
  return makeConcentrationMap(width, height, std::move(values), source);
}

} // namespace nx
