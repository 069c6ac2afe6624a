#pragma once
// Rendering a scene: TBB tasks over image tiles, each sample a pure function of
// (pixel, sample index, seed), so the image does not depend on the thread count.

#include <functional>
#include <optional>

#include "integrators/film.h"
#include "integrators/integrator.h"
#include "integrators/render_scene.h"
#include "io/spectral_exr.h"

namespace nx {

/// What to render beyond the scene itself.
struct RenderOptions {
  int samples = 0;                    ///< samples per pixel; 0 = the scene's <sampl>
  std::optional<uint32_t> seed;       ///< default: the scene's <seed>
  std::optional<SpectralBands> bands; ///< default: the scene's <bands>
  LightSampling lightSampling = LightSampling::Mis;
  SamplerKind sampler = SamplerKind::SobolOwen;
  int tileSize = 16;
  /// Runs the fluorescence-capable path tracer even without fluorescent materials (to
  /// measure what the feature costs when present but unused).
  bool forceFluorescencePath = false;
  /// Called after each finished tile with (finished, total); may be called from any thread,
  /// never concurrently.
  std::function<void(int, int)> progress;
};

/// Counters of a finished render.
struct RenderStats {
  double seconds = 0;
  uint64_t samples = 0;   ///< pixel samples
  uint64_t rays = 0;      ///< camera, scattered and shadow rays
  uint64_t nonFinite = 0; ///< samples dropped for a NaN or infinite value
};

/// A finished render.
struct RenderOutput {
  Film film;
  RenderStats stats;
  int samplesPerPixel = 0;
  uint32_t seed = 0;
};

/// Renders the scene with its mode (spectral_mcpt and mcpt: path tracing; rt: Whitted).
RenderOutput render(const RenderScene& scene, const RenderOptions& options);

/// The spectral image of a film: band means, and linear sRGB (D65) from XYZ with negatives
/// clamped to 0.
SpectralImage toSpectralImage(const Film& film);

/// An 8-bit preview: XYZ white-balanced from `white` to D65 (Bradford), converted to sRGB,
/// tone-mapped (Reinhard 2002). Returns interleaved RGB bytes, top row first.
std::vector<uint8_t> previewPixels(const Film& film, const Spectrum& white);

} // namespace nx
