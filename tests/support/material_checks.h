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

/// A fluorescent unit sphere of reflectance 0.3 (a dye absorbing at 420 nm, emitting 120 nm
/// above) made of `material` (its <material> and kind parameters), lit by a small lamp above
/// and seen from far along its axis: 6 x 6 pixels, 512 samples.
inline std::string fluorescentSphereScene(const std::string& material) {
  return sceneText(
      "<xres>6</xres><yres>6</yres><mode>spectral_mcpt</mode><depth>3</depth><sampl>512</sampl>",
      "<position>0,0,-100</position><look_at>0,0,0</look_at><fov>0.3</fov>",
      "<sphere><center>0,0,0</center><radius>1</radius>" + material +
          "<reflectance>0.3</reflectance><fluorescence><absorption>420</absorption><stokes>120"
          "</stokes><yield>0.8</yield></fluorescence></sphere><sphere><center>0,20,-20</center>"
          "<radius>3</radius><material>matte</material><reflectance>0</reflectance><emission>"
          "40</emission></sphere>");
}

} // namespace nx::test
