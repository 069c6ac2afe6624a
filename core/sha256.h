#pragma once
// SHA-256 (FIPS 180-4): a content digest strong enough that equal digests mean equal bytes (the
// mesh cache keys files by it instead of keeping their bytes).

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace nx {

/// The SHA-256 digest of `bytes`.
std::array<uint8_t, 32> sha256(std::string_view bytes);

/// The digest as 64 lowercase hexadecimal digits.
std::string sha256Hex(std::string_view bytes);

} // namespace nx
