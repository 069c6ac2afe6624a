#pragma once
// Relighting a relightable render (docs/relighting.md): the image under new emission spectra
// for some light groups is, per pixel and band, sum over groups g and excitation bins j
// of T_g(row, j) S_g(j), S_g(j) the new spectrum's average over bin j (the others keep the
// spectrum they were rendered with). Its variance is (sum D_g(row, j) S_g(j))^2 with D the
// replicates' signed half-differences: the same estimator as a render's variance channels.

#include <string>
#include <vector>

#include "io/spectral_exr.h"
#include "spectra/spectrum.h"

namespace nx {

/// A new emission spectrum for one light group, as its bin averages on the image's grid.
struct GroupSpectrum {
  std::string group;          ///< the light group (as the image lists it)
  std::vector<double> binned; ///< per bin of the image's RelightGrid
  std::string source;         ///< what it came from (a file name), for the attributes
};

/// The sources (RelightLayers::sources) of light group `group` of a relightable image; throws
/// nx::Error for an image without a transport, or listing its groups for another name.
std::vector<size_t> relightSourcesOf(const SpectralImage& image, const std::string& group);

/// Expected noise factor (relitExcitationNoiseFactor) from which relighting warns.
inline constexpr double kRelitNoiseWarning = 1.5;

/// The bin averages of `s` on `grid` for group `group` of `image`, with a warning in `warnings`
/// when `s` is tabulated over less than the bins the image's transport of that group reaches
/// (it is 0 there, as a render would take it), and when the group's fluoresced light relit
/// with it is expected at least kRelitNoiseWarning times as noisy as a direct render's. Throws for
/// a negative or non-finite value.
GroupSpectrum groupSpectrum(const SpectralImage& image, const std::string& group, const Spectrum& s,
                            double tableLoNm, double tableHiNm, const std::string& source,
                            std::vector<std::string>& warnings);

/// The same from a CSV file when `text` names one, else from a built-in emission name (A, D65,
/// F1-F12, blackbody:K, ... as a scene's <emission> reads it: scaled to the luminance of a flat
/// 1); throws naming both when it is neither.
GroupSpectrum groupSpectrumFromText(const SpectralImage& image, const std::string& group,
                                    const std::string& text, std::vector<std::string>& warnings);

/// The image under the new spectra: bands and their variances (Variance.S0...); XYZ, RGB and
/// Variance.Y from the relit bands (BandColour: the bands read as a spectrum, as for a file
/// without its own XYZ); sample counts, ids and depth; the reflected and fluoresced component
/// layers with their variances, relit, when the transport is split (RelightLayers::split); the
/// transport, other component layers and the white reference, which belong to the lighting
/// rendered, are not carried over. The attributes are kept, nxrender.relit names the spectra and
/// the render key says the image was relit. Throws nx::Error for an image without a transport, a
/// group it does not hold (listing those it does) or a group given twice.
SpectralImage relightImage(const SpectralImage& image, const std::vector<GroupSpectrum>& spectra);

} // namespace nx
