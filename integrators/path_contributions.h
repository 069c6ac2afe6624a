#pragma once
// Where the path tracer puts the light it finds: the radiance alone (every render), or also
// split by path class (the component AOVs: reflected / fluoresced, direct / indirect, light
// group). Each contribution goes to exactly one layer of each split, so every split sums to the
// radiance per sample.

#include <cstdint>
#include <vector>

#include "io/relight_layers.h"
#include "spectra/sampled_wavelengths.h"
#include "spectra/spectrum.h"

namespace nx {

/// Lanes whose wavelength differs between `a` and `b` (a re-radiation event), one bit each.
inline uint64_t shiftedLanes(const SampledWavelengths& a, const SampledWavelengths& b) {
  uint64_t mask = 0;
  for (int i = 0; i < kLanes; ++i)
    if (a.lambda[i] != b.lambda[i]) mask |= uint64_t{1} << i;
  return mask;
}

/// The class of the path a contribution arrived by.
struct PathClass {
  uint64_t shifted = 0; ///< lanes with at least one re-radiation event on the path (bit per lane)
  int scatterings = 0;  ///< scattering events between the emitter and the camera
  uint16_t group = 0;   ///< the emitter's light group (RenderScene::lightGroups)
  uint16_t source = 0;  ///< its relight source (RelightSpectra; 0 unless relightable)
  /// The wavelengths the light left the emitter with, per lane (its excitation wavelengths)
  const SampledWavelengths* emitted = nullptr;
};

/// The plain sink: the radiance alone (the path tracer then tracks no path class).
struct RadianceSink {
  static constexpr bool kClasses = false; ///< the path tracer need not track classes
  SampledSpectrum L;                      ///< radiance of the sample
  /// Adds contribution c (its class is ignored).
  void add(const SampledSpectrum& c, const PathClass&) { L += c; }
};

/// Which layers a component render keeps: offsets into its per-sample layer spectra, -1 for a
/// split not asked for.
struct ComponentLayout {
  int classes = -1; ///< reflected, fluoresced, direct, indirect from here (--aov components)
  int groups = -1;  ///< one layer per light group from here (--aov lightgroups)
  int count = 0;    ///< layers in all
  /// True when some split is kept.
  bool any() const { return count > 0; }
};

/// The component sink: the radiance and its layers (zeroed by the caller for each sample).
struct ComponentSink {
  static constexpr bool kClasses = true; ///< the path tracer tracks path classes
  SampledSpectrum L;                     ///< radiance of the sample
  SampledSpectrum* layers = nullptr;     ///< layout.count spectra
  const ComponentLayout* layout = nullptr;

  /// Adds contribution c to the radiance and to one layer of each split: reflected (no lane
  /// shifted) or fluoresced per lane; direct (emission seen directly or after one scattering)
  /// or indirect; its light group.
  void add(const SampledSpectrum& c, const PathClass& k) {
    L += c;
    if (layout->classes >= 0) {
      SampledSpectrum reflected = c, fluoresced;
      for (int i = 0; i < kLanes; ++i)
        if ((k.shifted >> i) & 1u) fluoresced[i] = c[i], reflected[i] = 0;
      SampledSpectrum* split = layers + layout->classes;
      split[0] += reflected;
      split[1] += fluoresced;
      split[k.scatterings <= 1 ? 2 : 3] += c;
    }
    if (layout->groups >= 0) layers[layout->groups + k.group] += c;
  }
};

/// One lane of a contribution to a relightable render: its transport per unit emission
/// spectrum, the relight source and the excitation bin it left the emitter in.
struct RelightContribution {
  float value;     ///< the contribution with the group's spectrum taken out (its factor kept)
  int32_t bin;     ///< excitation bin (RelightGrid), -1 outside the grid
  uint16_t group;  ///< light group
  uint8_t lane;    ///< the lane (its sensor wavelength)
  uint8_t shifted; ///< 1 when the path re-radiated the lane (fluoresced light), 0 reflected
};

/// Where a relightable render's sink puts a sample's contributions (cleared per sample).
struct RelightRecorder {
  const std::vector<Spectrum>* spectra = nullptr; ///< per source, RelightSpectra::ofSource
  RelightGrid grid;
  std::vector<RelightContribution> contributions; ///< this sample's, lane by lane
};

/// The sink of a relightable render: the scene was built with flat unit spectra
/// (RelightSpectra), so each contribution c arrives per unit spectrum; the radiance (and any
/// component layer) receives c S_s(emitted lanes), the recorder c itself with its bins.
struct RelightSink {
  static constexpr bool kClasses = true; ///< the path tracer tracks path classes
  ComponentSink components;              ///< the radiance and any component layers
  RelightRecorder* recorder = nullptr;   ///< null: only apply the spectra (white reference)
  const std::vector<Spectrum>* spectra = nullptr;

  /// Adds contribution c (per unit spectrum of source k.source, left at k.emitted).
  void add(const SampledSpectrum& c, const PathClass& k) {
    SampledSpectrum s;
    (*spectra)[k.source].evaluate(*k.emitted, s);
    components.add(c * s, k);
    if (!recorder) return;
    for (int i = 0; i < kLanes; ++i)
      if (c[i] != 0)
        recorder->contributions.push_back({c[i], recorder->grid.binOf(k.emitted->lambda[i]),
                                           k.source, static_cast<uint8_t>(i),
                                           static_cast<uint8_t>((k.shifted >> i) & 1u)});
  }
};

} // namespace nx
