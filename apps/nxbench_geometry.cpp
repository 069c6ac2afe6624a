// nxbench-geometry: Embree ray throughput on nxrender's geometry (sphere user geometry,
// planes in the analytic pass), the physical limit the path tracer is compared against.
//
//   nxbench-geometry [--rays N] [--seconds S]
//
// For 8, 1000 and 100000 random spheres plus 2 planes, on 1 and 2 threads, it traces
// incoherent rays (random origins inside the scene's box, random directions) and prints
// closest-hit and occlusion rays per second.

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cstdio>

#include "accel/geometry_scene.h"
#include "apps/command_line.h"
#include "core/hash.h"
#include "core/math_util.h"
#include "integrators/sampling.h"

namespace {

using namespace nx;

float rnd(uint32_t a, uint32_t b) {
  return bitsToUnitFloat(hash4(a, b, 0xbe, 0));
}

Vec3 direction(uint32_t k) {
  return sampleUniformSphere({rnd(k, 1), rnd(k, 2)});
}

struct Result {
  double closest, occluded;
};

Result measure(const GeometryScene& g, double box, int threads, uint64_t rays) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<size_t>(threads));
  std::atomic<uint64_t> hits{0};
  auto makeRay = [&](uint64_t i) {
    const uint32_t k = static_cast<uint32_t>(i);
    Ray r;
    r.o = Vec3(static_cast<float>(box * (2 * rnd(k, 3) - 1)), static_cast<float>(box * rnd(k, 4)),
               static_cast<float>(box * (2 * rnd(k, 5) - 1)));
    r.d = direction(k);
    return r;
  };
  auto run = [&](bool occlusion) {
    const auto start = std::chrono::steady_clock::now();
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, rays, 4096),
                      [&](const tbb::blocked_range<uint64_t>& range) {
                        uint64_t local = 0;
                        SurfaceHit h;
                        for (uint64_t i = range.begin(); i != range.end(); ++i) {
                          const Ray r = makeRay(i);
                          local += occlusion ? g.occluded(r) : g.intersect(r, h);
                        }
                        hits += local;
                      });
    return static_cast<double>(rays) /
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  return {run(false), run(true)};
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"Embree ray throughput on nxrender's sphere and plane geometry"};
  uint64_t rays = 2000000;
  app.add_option("--rays", rays, "Rays per measurement (default 2e6)")
      ->check(nx::numberIn(1000, 1000000000));
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxbench-geometry"); status >= 0)
    return status;
  try {
    EmbreeDevice device;
    std::printf("%-10s %-7s %-8s %16s %16s\n", "spheres", "planes", "threads", "closest Mrays/s",
                "occluded Mrays/s");
    for (int n : {8, 1000, 100000}) {
      // Spheres in a box whose size keeps the density similar: radius ~ 1, box ~ n^(1/3) * 4.
      const double box = 4.0 * std::cbrt(static_cast<double>(n));
      std::vector<SphereShape> spheres;
      for (int i = 0; i < n; ++i) {
        const uint32_t k = 1000000u + static_cast<uint32_t>(i);
        spheres.push_back(
            {Vec3d(box * (2 * rnd(k, 6) - 1), box * rnd(k, 7), box * (2 * rnd(k, 8) - 1)),
             0.3 + 0.7 * rnd(k, 9)});
      }
      const std::vector<PlaneShape> planes{{Vec3d(0, 1, 0), 0.0}, {Vec3d(0, 0, -1), -box}};
      for (int nPlanes : {2, 0}) {
        GeometryScene g(device, spheres, nPlanes ? planes : std::vector<PlaneShape>{}, {});
        measure(g, box, 2, rays / 10); // warm caches and Embree's thread pool
        for (int threads : {1, 2}) {
          if (nPlanes == 0 && threads == 2) continue; // the plane pass's cost: one thread suffices
          const Result r = measure(g, box, threads, rays);
          std::printf("%-10d %-7d %-8d %16.2f %16.2f\n", n, nPlanes, threads, r.closest * 1e-6,
                      r.occluded * 1e-6);
        }
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nxbench-geometry: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
