#pragma once
// CIE 1931 2-degree colour matching functions and XYZ colour values.

#include <array>

namespace nx {

/// Shortest wavelength of the CIE tables nxrender uses (nm).
inline constexpr int kCieMinNm = 360;
/// Longest wavelength of the CIE tables (nm).
inline constexpr int kCieMaxNm = 830;
/// Number of 1 nm samples in [kCieMinNm, kCieMaxNm].
inline constexpr int kCieSamples = kCieMaxNm - kCieMinNm + 1;
/// Integral of y-bar over 360-830 nm: the 1 nm sum of the table (CIE quotes 106.857).
inline constexpr double kCieYIntegral = 106.856917;

/// Tristimulus values X, Y, Z.
struct Xyz {
  double x = 0, y = 0, z = 0;
};

/// The CIE 1931 2-degree colour matching functions at 1 nm, 360-830 nm.
struct CieTables {
  std::array<double, kCieSamples> xBar, yBar, zBar;
};

/// The tables, parsed once from the embedded CIE data file.
const CieTables& cieTables();

/// Colour matching functions at wavelength nm (linear between 1 nm samples, 0 outside).
Xyz cieCmf(double nm);

/// Chromaticity x = X / (X + Y + Z).
inline double chromaticityX(const Xyz& c) {
  return c.x / (c.x + c.y + c.z);
}
/// Chromaticity y = Y / (X + Y + Z).
inline double chromaticityY(const Xyz& c) {
  return c.y / (c.x + c.y + c.z);
}

} // namespace nx
