#pragma once
// Rows of numbers written inline (a mesh's <vertices>, <faces>, <normals>, <uv>): made from
// numbers (Python's arrays) or read from text, checked, and written back as text that reads to
// the same numbers bit for bit.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/params/scene_values.h"

namespace nx {

/// Rows of `columns` reals; throws nx::Error "expected ..., found ..." (no location) when the
/// count is not a positive multiple of `columns` or a value is not finite.
ArrayDesc realRows(std::vector<float> values, uint32_t columns);

/// Rows of `columns` indices; throws as realRows when the count is not a positive multiple.
ArrayDesc indexRows(std::vector<uint32_t> values, uint32_t columns);

/// Rows read from text: numbers separated by white space, rows by commas (each of `columns`
/// numbers; without commas the numbers run on); reals rounded once to float, indices whole
/// numbers in [0, 2^32); throws as realRows.
ArrayDesc arrayFromText(std::string_view text, bool indices, uint32_t columns);

/// The rows as text ("x y z, x y z, ..."): the shortest digits that read back to each float.
std::string arrayText(const ArrayDesc& a);

} // namespace nx
