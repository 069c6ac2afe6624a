#pragma once
// Shared pieces of the material tests: a fixed set of lane wavelengths and the error message
// of a one-sphere scene.

#include <string>

#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "spectra/sampled_wavelengths.h"
#include "support/errors.h"
#include "support/render_checks.h"

namespace nx::test {

/// Lanes at 450, 480, 510, ... nm.
inline SampledWavelengths laneWavelengths() {
  SampledWavelengths l;
  for (int i = 0; i < kLanes; ++i) l.lambda[i] = 450.0f + 30.0f * static_cast<float>(i);
  return l;
}

/// The error building a scene of one unit sphere whose children (material and parameters) are
/// `body` raises (named t.scn), or "" when it builds.
inline std::string sphereSceneError(const std::string& body) {
  return errorMessage([&] {
    (void)resolveRenderScene(parseScene(
        sceneText("<xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode>",
                  "<position>0,0,-5</position><look_at>0,0,0</look_at>",
                  "<sphere><center>0,0,0</center><radius>1</radius>" + body + "</sphere>"),
        "t.scn"));
  });
}

} // namespace nx::test
