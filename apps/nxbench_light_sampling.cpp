// nxbench-light-sampling: NEE + MIS against BSDF sampling alone and NEE alone.
//
//   nxbench-light-sampling [--spp N] [--reference-spp N]
//
// A floor lit by a small bright sphere light inside a large emitting dome (a sky) (the scene of the
// unit test). A high-spp MIS render is the reference; each strategy renders at the same spp and the
// RMSE of luminance against the reference is printed.

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>

#include "apps/command_line.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"

namespace {

const char* kScene =
    "<scene><settings><xres>48</xres><yres>36</yres><mode>spectral_mcpt</mode><depth>3</"
    "depth><sampl>16</sampl>"
    "</settings><camera><position>0,3,-6</position><look_at>0,0,0</look_at><fov>50</fov></camera>"
    "<plane><normal>0,1,0</normal><distance>0</distance><material>matte</"
    "material><reflectance>0.6</reflectance></plane>"
    "<sphere><center>0,1.2,0</center><radius>0.08</radius><material>matte</material><emission>300</"
    "emission></sphere>"
    "<sphere><center>0,0,0</center><radius>100</radius><material>matte</material><emission>1</"
    "emission></sphere>"
    "</scene>";

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"RMSE of NEE+MIS, BSDF-only and NEE-only at equal samples per pixel"};
  int spp = 16, refSpp = 4096;
  app.add_option("--spp", spp, "Samples per pixel of each strategy (default 16)")
      ->check(nx::numberIn(1, 1 << 20));
  app.add_option("--reference-spp", refSpp, "Samples per pixel of the reference (default 4096)")
      ->check(nx::numberIn(1, 1 << 24));
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxbench-light-sampling");
      status >= 0)
    return status;
  try {
    const nx::RenderScene scene = nx::buildRenderScene(nx::parseScene(kScene, "light-sampling"));
    nx::RenderOptions ro;
    ro.samples = refSpp;
    ro.seed = 1000;
    const nx::RenderOutput ref = nx::render(scene, ro);
    std::printf("%-10s %6s %12s %10s\n", "strategy", "spp", "RMSE (Y)", "seconds");
    const std::pair<const char*, nx::LightSampling> strategies[] = {
        {"NEE+MIS", nx::LightSampling::Mis},
        {"BSDF", nx::LightSampling::BsdfOnly},
        {"NEE", nx::LightSampling::NeeOnly}};
    for (const auto& [name, strategy] : strategies) {
      nx::RenderOptions o;
      o.samples = spp;
      o.lightSampling = strategy;
      const nx::RenderOutput out = nx::render(scene, o);
      double se = 0;
      for (int y = 0; y < out.film.height(); ++y)
        for (int x = 0; x < out.film.width(); ++x) {
          const double d = out.film.xyzMean(x, y).y - ref.film.xyzMean(x, y).y;
          se += d * d;
        }
      std::printf("%-10s %6d %12.5f %10.3f\n", name, spp,
                  std::sqrt(se / (out.film.width() * out.film.height())), out.stats.seconds);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nxbench-light-sampling: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
