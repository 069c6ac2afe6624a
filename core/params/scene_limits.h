#pragma once
// The ranges of a scene's numeric parameters, shared by the scene-file reader and the Python
// module's scene editing, so a value refused in one is refused in the other.

namespace nx {

/// An allowed range [lo, hi] (or (lo, hi] when openLow) and what the value is.
struct ParameterRange {
  double lo, hi;
  bool openLow;
  const char* what;
  /// True when v lies in the range.
  bool contains(double v) const { return v >= lo && v <= hi && !(openLow && v == lo); }
};

inline constexpr double kMaxSceneCoordinate = 1e12; ///< far below Embree's limit of 1.8e18
inline constexpr int kMaxResolution = 65536;        ///< pixels per side

/// A factor on a spectrum (a medium coefficient's scale="..."): positive and finite.
inline constexpr ParameterRange kPositiveScaleRange{0, 1e300, true, "a scale factor"};
/// The distance (scene units) at which a lamp's spectral irradiance was measured.
inline constexpr ParameterRange kMeasuredDistanceRange{0, kMaxSceneCoordinate, true,
                                                       "a measuring distance"};
/// The factor on an emission: non-negative and finite (0: a lamp switched off, in a sweep).
inline constexpr ParameterRange kEmissionScaleRange{0, 1e300, false, "an emission scale"};
/// A reflectance colour channel.
inline constexpr ParameterRange kUnitRange{0, 1, false, "a colour channel"};
inline constexpr ParameterRange kFovRange{0, 179, true, "a horizontal field of view in degrees"};
inline constexpr ParameterRange kRoughnessRange{0, 1, false, "a roughness"};
inline constexpr ParameterRange kRadiusRange{0, kMaxSceneCoordinate, true, "a radius"};
/// A plane's signed distance from the origin along its normal.
inline constexpr ParameterRange kPlaneDistanceRange{-kMaxSceneCoordinate, kMaxSceneCoordinate,
                                                    false, "a plane distance"};
inline constexpr ParameterRange kIorRange{1, 10, false, "an index of refraction"};
inline constexpr ParameterRange kAbsorptionRange{200, 1000, false, "an absorption peak in nm"};
inline constexpr ParameterRange kStokesRange{0, 1000, false, "a Stokes shift in nm"};
inline constexpr ParameterRange kWidthRange{0, 500, true, "a width in nm"};
inline constexpr ParameterRange kSkewRange{0, 1000, false, "a skew magnitude"};
inline constexpr ParameterRange kYieldRange{0, 1, false, "a quantum yield"};
/// A surface dye's relative concentration (a share of its peak absorptance).
inline constexpr ParameterRange kConcentrationRange{0, 1, false, "a relative concentration"};
inline constexpr ParameterRange kPeakRange{0, 1, false, "a peak absorptance"};
/// An EEM's scatter bands: full widths in nm (0: none removed) and a Raman shift in cm^-1.
inline constexpr ParameterRange kScatterWidthRange{0, 200, false, "a band's full width in nm"};
inline constexpr ParameterRange kRamanShiftRange{0, 10000, true, "a Raman shift in cm^-1"};
/// A reference dye's quantum yield and absorptance (positive: they divide).
inline constexpr ParameterRange kReferenceYieldRange{0, 1, true, "a reference quantum yield"};
inline constexpr ParameterRange kReferenceAbsorptanceRange{0, 1, true, "a reference absorptance"};
/// A wavelength in nm of an instrument's range.
inline constexpr ParameterRange kInstrumentNmRange{100, 2000, false, "a wavelength in nm"};
/// A dye's peak absorption coefficient in a medium (per scene unit of length).
inline constexpr ParameterRange kPeakCoefficientRange{
    0, 1e9, true, "a peak absorption coefficient per unit length"};
/// GGX roughness alpha of a conductor (0: smooth; 1 is already a very rough surface).
inline constexpr ParameterRange kAlphaRange{0, 1, false, "a GGX roughness alpha"};
inline constexpr ParameterRange kOrenNayarRange{0, 1, false, "an Oren-Nayar roughness sigma"};
/// A thin-film coating's thickness in nm (interference needs it below a few micrometres).
inline constexpr ParameterRange kCoatingThicknessRange{0, 1e5, true, "a coating thickness in nm"};
/// Henyey-Greenstein g: |g| = 1 would be a delta lobe (excluded by a margin).
inline constexpr ParameterRange kPhaseGRange{-0.999, 0.999, false,
                                             "a Henyey-Greenstein g (mean cosine)"};

} // namespace nx
