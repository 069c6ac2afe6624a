#pragma once
// Visibility through media: the fraction of light that travels a shadow ray's segment, per
// lane. Interface surfaces (index-matched boundaries) are passed through, updating the media
// the ray is in; any other surface blocks it. Homogeneous media attenuate exactly
// (Beer-Lambert per lane), so no ratio tracking is needed.

#include <utility>
#include <vector>

#include "core/ray.h"
#include "integrators/integrator.h"
#include "integrators/media/medium_stack.h"
#include "integrators/render_scene.h"

namespace nx {

/// exp(-sigma_t * length) per lane of the medium `medium` (-1: none, 1) at `lambda`; an
/// infinite length gives 0 where sigma_t > 0 and 1 where it is 0.
SampledSpectrum mediumTransmittance(const RenderScene& scene, int medium,
                                    const SampledWavelengths& lambda, float length);

/// What a shadow ray passed through (for differentiated renders): the lengths it ran in each
/// medium and the thin walls it crossed (their materials).
struct ShadowCrossings {
  std::vector<std::pair<int, float>> media; ///< (medium index, length)
  std::vector<uint32_t> walls;              ///< material indices
  /// Empties it (keeps the capacity).
  void clear() {
    media.clear();
    walls.clear();
  }
};

/// Transmittance along a shadow ray (as shadowRayTo builds it: valid for t < tMax, direction
/// not necessarily unit) that starts inside the media of `media`, at the lanes' wavelengths.
/// Zero when a surface other than an interface lies in the way. `crossings`, when given,
/// receives what the ray passed through.
SampledSpectrum shadowTransmittance(const RenderScene& scene, const Ray& ray, MediumStack media,
                                    const SampledWavelengths& lambda, TraceCounters& counters,
                                    ShadowCrossings* crossings = nullptr);

} // namespace nx
