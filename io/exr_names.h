#pragma once
// What OpenEXR can store as a name: channel and attribute names of at most 255 bytes (longer
// ones are cut without a word, so two long light groups shared one channel). The names a scene
// derives from its light groups are bounded here, before any render.

#include <cstddef>
#include <string>

namespace nx {

/// Longest channel or attribute name OpenEXR stores (Imf::Name holds 255 bytes and a NUL).
inline constexpr size_t kMaxExrNameBytes = 255;

/// The longest channel or attribute name a light group called `group` can give a file: its
/// layer's variance channels (Variance.light.NAME.S0.<band>nm), its transport's
/// half-differences (HalfDifference.relight.NAME.N.T.<excitation>nm.<band>nm, with the suffix
/// of a further spectrum up to .65535) and its spectrum attribute, at the longest wavelength
/// text.
size_t longestExrNameOfLightGroup(const std::string& group);

/// The longest light group name whose every derived name fits kMaxExrNameBytes.
size_t longestLightGroupName();

/// Throws nx::Error naming `path` unless `name` (a channel's or an attribute's, as `what`
/// says) is 1-255 bytes: what OpenEXR would cut.
void checkExrName(const std::string& path, const std::string& name, const char* what);

} // namespace nx
