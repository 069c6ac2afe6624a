#pragma once
// Relighting targets (docs/relighting.md, "Relighting targets"): the spectra a relightable render
// is told it will be relit to. The render then chooses lights by their power under them and
// draws fluorescent excitation towards them (next-event estimation's guided excitation), so that
// an image relit to a narrow lamp is about as noisy as a direct render under it. Without targets,
// relighting estimates how much noisier than a direct render a relit image will be.

#include <string>
#include <vector>

#include "integrators/render_scene.h"
#include "io/scene_desc.h"
#include "io/spectral_exr.h"

namespace nx {

/// An emission spectrum named by text: a CSV file (two columns nm,value) when `text` names one,
/// else a built-in emission name (A, D65, F1-F12, blackbody:K, ... scaled as an <emission>),
/// with the range [loNm, hiNm] outside which it is 0 (a table's ends). Throws nx::Error naming
/// both forms when it is neither, or naming the file for a negative or non-finite value.
struct TextSpectrum {
  Spectrum spectrum;
  double loNm = 300, hiNm = 1100;
};
TextSpectrum spectrumFromText(const std::string& text);

/// A target from "[GROUP=]FILE|NAME" (`option` names it in errors): the spectrum checked as an
/// <emission> (within [0, 1e12], not 0 everywhere over 300-1100 nm).
RelightTargetDesc relightTargetFromText(const std::string& text, const std::string& option);

/// Checks `target` as relightTargetFromText does (a spectrum given from Python); throws
/// nx::Error naming `where`.
void checkRelightTarget(const RelightTargetDesc& target, const std::string& where);

/// Sets a relightable build's sampling for `targets` (RelightSpectra::samplingOfSource and
/// targetsOfSource): per source the targets of its group (a target without a group counts for
/// every group), each an excitation guide, and their mixture for the choice among lights (the
/// mean of their shapes normalised to unit integral over 300-1100 nm, scaled to their mean
/// integral); its own spectrum for a group without targets; both empty without targets. Throws
/// nx::Error for a target of a group the scene does not have (listing those it has) and for
/// more than kMaxExcitationGuides targets of one group.
void setRelightTargets(RenderScene& scene, const std::vector<RelightTargetDesc>& targets);

/// How much noisier than a direct render under it an image relit with a spectrum is expected
/// to be (standard deviations at equal samples), in its worst band.
struct RelitNoise {
  double factor = 1;          ///< the estimate (from the excitation draws' mismatch alone)
  int band = -1;              ///< the band (-1: none is worse than 1)
  double fluorescedShare = 0; ///< its share of fluoresced light, relit
};

/// The expected noise of `image` relit with `binned` (bin averages on its grid) for the sources
/// `sources` (a light group), against a direct render under that spectrum. Per pixel and band the
/// transport tells how often each choice of a draw (the elastic one, each excitation bin) was
/// made: the re-radiation matrices' choice, or, in a targeted render, the best of it and the
/// draws towards each of its excitation guides (RelightLayers::guides). Weighted by the relit
/// spectrum, the second moment F = E[T S^2] E[T] / E[T S]^2 against drawing in proportion to T S
/// (as a direct render's guided excitation nearly does) gives the estimate sqrt(F), pooled over the
/// pixels where fluoresced light is most of the band (by their relit values squared): the
/// excitation draws' share of the noise alone (the rest, light positions and directions, and the
/// direct render's own imperfect guiding move the measured ratio either way: docs/relighting.md
/// compares them). Bands holding less than 5% of the brightest band's light (in that measure) are
/// left out.
RelitNoise relitNoiseFactor(const SpectralImage& image, const std::vector<size_t>& sources,
                            const std::vector<double>& binned);

} // namespace nx
