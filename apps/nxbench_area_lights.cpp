// nxbench-area-lights: emitting triangles (a quad, PLY icospheres) sampled by solid angle
// against sampling by area, at equal samples per pixel, and the time to equal error.
//
//   nxbench-area-lights [--threads N] [--spp N] [--repeats N] [scene.scn]
//
// Each strategy renders the scene (default scenes/area_lights.scn) --repeats times with
// different seeds; per lit pixel and band (and per pixel in luminance) the relative variance of
// one render is measured about the mean. Time to equal error is variance times time per
// sample: the ratio of the two strategies' is what the faster-converging one saves. A third
// row draws the wavelengths with stratified lanes (RenderOptions::stratifiedLanes).

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <cstdio>
#include <string>

#include "apps/command_line.h"
#include "apps/seed_statistics.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"

int main(int argc, char** argv) {
  CLI::App app{"Triangle lights by solid angle against by area: noise, time, time to equal error"};
  int threads = 2, spp = 16, repeats = 6;
  std::string scenePath = NX_SOURCE_DIR "/scenes/area_lights.scn";
  app.add_option("--threads", threads, "Worker threads (default 2)")->check(nx::numberIn(1, 4096));
  app.add_option("--spp", spp, "Samples per pixel (default 16)")->check(nx::numberIn(1, 1 << 20));
  app.add_option("--repeats", repeats, "Seeds per strategy (default 6)")
      ->check(nx::numberIn(2, 1000));
  app.add_option("scene", scenePath, "Scene (default scenes/area_lights.scn)");
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxbench-area-lights"); status >= 0)
    return status;
  try {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              static_cast<size_t>(threads));
    const nx::RenderScene scene = nx::buildRenderScene(nx::loadScene(scenePath));
    std::printf("%s, %d spp, %d seeds, %d threads\n", scenePath.c_str(), spp, repeats, threads);
    std::printf("%-18s %14s %14s %10s\n", "triangle lights", "band noise", "luminance noise",
                "ns/sample");
    // [strategy][band, luminance]: variance x time; strategies: by area, by solid angle, by
    // solid angle with stratified lanes (RenderOptions::stratifiedLanes).
    double work[3][2] = {};
    const char* names[3] = {"by area", "by solid angle", "+ stratified lanes"};
    for (int i = 0; i < 3; ++i) {
      nx::RenderOptions o;
      o.samples = spp;
      o.triangleLightSampling =
          i == 0 ? nx::TriangleLightSampling::Area : nx::TriangleLightSampling::SolidAngle;
      o.stratifiedLanes = i == 2;
      const nx::bench::SeedStatistics st = nx::bench::seedStatistics(scene, o, repeats);
      const double band = nx::bench::litNoise(st), luminance = nx::bench::litNoiseY(st);
      work[i][0] = band * band * st.nsPerSample;
      work[i][1] = luminance * luminance * st.nsPerSample;
      std::printf("%-18s %14.4f %14.4f %10.0f\n", names[i], band, luminance, st.nsPerSample);
    }
    std::printf("time to equal error, solid angle / area: %.3f per band, %.3f in luminance\n",
                work[1][0] / work[0][0], work[1][1] / work[0][1]);
    std::printf("time to equal error, stratified lanes / not: %.3f per band, %.3f in luminance\n",
                work[2][0] / work[1][0], work[2][1] / work[1][1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nxbench-area-lights: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
