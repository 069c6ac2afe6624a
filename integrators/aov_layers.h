#pragma once
// Ground-truth layers of what the camera sees first (docs/datasets.md): shading and geometric
// normals, positions, uv, albedo and the dye's spectra, evaluated per camera sample at the
// sample's own film position and averaged over the pixel like the radiance (so they line up
// with it, and merge and resume as it does).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/ray.h"
#include "core/sampler.h"
#include "io/aov_names.h"
#include "spectra/reradiation_matrix.h"
#include "spectra/sampled_wavelengths.h"
#include "spectra/sensor.h"

namespace nx {

struct RenderScene;

/// The layers a render keeps and their evaluation for one camera ray.
class AovEvaluator {
public:
  /// For `scene` (which must outlive it), keeping `kinds` (each once, in kAovKinds order) for
  /// the output bands `bands`. Throws nx::Error for a kind given twice.
  AovEvaluator(const RenderScene& scene, std::vector<AovKind> kinds, const Sensor& bands);
  /// The kinds kept, in channel order.
  const std::vector<AovKind>& kinds() const { return kinds_; }
  /// Channels of all layers.
  int channels() const { return channels_; }
  /// The first channel of kind k (-1 when not kept).
  int offset(AovKind k) const;
  /// Fills out[channels()] for the first hit of `ray` (all 0 where it hits nothing); `rng`
  /// draws the directions of the directional albedo (non-matte kinds).
  void evaluate(const Ray& ray, PixelSampleStream& rng, float* out) const;

private:
  void albedo(const struct SurfaceHit& hit, const Ray& ray, PixelSampleStream& rng,
              float* out) const;
  void fluorescence(struct SurfaceHit& hit, float* out) const;

  const RenderScene& scene_;
  std::vector<AovKind> kinds_;
  int channels_ = 0, bands_ = 0;
  /// Per band, kNodes wavelengths at the quantiles (j + 1/2) / kNodes of its response: the
  /// band's mean of a spectrum is the mean over its nodes.
  static constexpr int kNodes = 4;
  std::vector<float> nodes_; ///< [band][node]
  /// What a hit on a material gives without tracing, per band (empty where it does not apply):
  /// a matte's (a mixture's) reflectance and, with a dye, its elastic part at concentration 1
  /// (untextured materials); the dye's photons re-emitted per photon absorbed at each excitation
  /// wavelength (sum_o M[i][o] l_o / l_i) and its emission per nm (c(o) normalised to area 1).
  struct MaterialBands {
    std::vector<float> reflectance, elastic, absorption, emission;
  };
  std::vector<MaterialBands> materials_; ///< [material]
  /// The band nodes first, first + 1, ... in the lanes (the last node repeated past the end).
  SampledWavelengths nodeLanes(int first) const;
  /// The band means of the spectrum `lanes` gives for a set of wavelengths.
  template <class F>
  std::vector<float> bandMeans(F&& lanes) const;
};

} // namespace nx
