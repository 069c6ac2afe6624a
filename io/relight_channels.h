#pragma once
// How a relightable render's transport is stored in its EXR (docs/relighting.md): one float
// channel per light group and pattern entry, named by both wavelengths in the bispectral
// spirit of Fichet et al. 2021 ("T.<excitation>.<emission>" within a layer per group):
//   relight.<source>.T.<excitation bin centre>nm.<band>nm             all light of the pair
//   relight.<source>.fluoresced.T.<excitation bin centre>nm.<band>nm  its fluoresced part
// (the second where both reflected and re-radiated light reach the pair), each with
// HalfDifference.<channel> (the replicates' signed half-difference), and the attributes
// nxrender.relightSources, nxrender.relightGrid, nxrender.relightSpectrum.<source> and
// nxrender.relightDiagonal (which bins reflected light reaches in each band).

#include <map>
#include <string>
#include <vector>

#include "io/relight_layers.h"

namespace nx {

/// Prefix of the half-difference channels of the transport.
inline constexpr const char* kHalfDifferencePrefix = "HalfDifference.";
/// The attribute listing the transport's sources (comma-separated, in layer order): light
/// groups, NAME.2, NAME.3 for a group's further spectra.
inline constexpr const char* kRelightSourcesAttribute = "nxrender.relightSources";
/// The attribute giving the excitation grid: "FIRST:END:STEP" in nm.
inline constexpr const char* kRelightGridAttribute = "nxrender.relightGrid";
/// The attribute prefix of each group's rendered spectrum (bin averages, comma-separated).
inline constexpr const char* kRelightSpectrumAttribute = "nxrender.relightSpectrum.";

/// The attribute prefix of each source's excitation guides (bin averages) in a render told its
/// relighting targets (--relight-for): nxrender.relightGuide.<source>.<k>, k from 1.
inline constexpr const char* kRelightGuideAttribute = "nxrender.relightGuide.";
/// The attribute giving, per band row, the excitation range reflected light reaches (the bins
/// overlapping the band's support), "LO:HI" in nm or "none", comma-separated: the entries
/// outside it hold fluoresced light only. Files without it do not split the transport.
inline constexpr const char* kRelightDiagonalAttribute = "nxrender.relightDiagonal";
/// The layer of a source's fluoresced parts: relight.<source>.fluoresced.T.<...>.
inline constexpr const char* kRelightFluorescedLayer = "fluoresced";

/// relight.<source>.T.<excitation>.<band>: the channel of a source's transport from the
/// excitation wavelength to the band, both as the spectral channels write them.
std::string relightChannelText(const std::string& source, const std::string& excitation,
                               const std::string& band);

/// The channel of group g's entry e; `bandText` gives each band row's wavelength as its
/// spectral channel names it ("550,000000nm").
std::string relightChannelName(const RelightLayers& rl, size_t g, size_t e,
                               const std::vector<std::string>& bandText);

/// Largest transport value a relightable file may hold: what a spectrum at the emission limit
/// (kMaxEmission) relights into a float (3.4e38 / 1e12). A render never comes near it.
inline constexpr double kMaxTransportValue = 3.4e26;

/// Throws nx::Error naming `path`, the channel and the pixel unless every transport value of
/// rl (width x height pixels per channel) is within [0, kMaxTransportValue] and every
/// half-difference within +-kMaxTransportValue (a file tampered with: negative or 3e38 values
/// were relit silently).
void checkRelightValues(const RelightLayers& rl, const std::vector<std::string>& channels,
                        int width, int height, const std::string& path);

/// The attributes describing rl (groups, grid, spectra).
std::map<std::string, std::string> relightAttributes(const RelightLayers& rl);

/// Reads rl's description back from an image's attributes (removing them) and its channel
/// names: groups, grid, spectra and the pattern (the entries every group has). Returns the
/// channel of each (group, entry), in rl's order; empty when the image holds no transport.
/// Errors name `path` and what was expected.
std::vector<std::string> parseRelightChannels(std::map<std::string, std::string>& attributes,
                                              const std::vector<std::string>& channels,
                                              const std::vector<std::string>& bandText,
                                              const std::string& path, RelightLayers& rl);

} // namespace nx
