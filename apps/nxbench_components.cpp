// nxbench-components: what each step of a path costs, on a scene's own geometry and materials.
//
//   nxbench-components [scene.scn] [--records N]
//
// Camera rays of the scene give N surface points (with their wavelengths); each step the path
// tracer runs per sample or per vertex is then timed alone over those inputs on one thread
// (fastest of five repeats), in ns per call. Beside it: the render's time per sample and per
// ray, to see how the steps add up.

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <cstdio>
#include <vector>

#include "apps/bench_util.h"
#include "apps/command_line.h"
#include "core/error.h"
#include "core/ray_offset.h"
#include "integrators/film.h"
#include "integrators/fluorescent_vertex.h"
#include "integrators/integrator.h"
#include "integrators/materials/bsdf.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "spectra/wavelength_sampler.h"

namespace {

using namespace nx;

// A surface point reached by a camera ray, with what shading it needs.
struct Record {
  Ray ray;
  SurfaceHit hit;
  SampledWavelengths lambda;
  uint32_t pixel = 0;
};

// ns per call of f(i) for i in [0, n), fastest of five repeats (the machine's noise is
// one-sided).
template <typename F>
double nsPerCall(size_t n, F&& f) {
  const double s = bench::fastestSeconds(5, [&] {
    for (size_t i = 0; i < n; ++i) f(i);
  });
  return s * 1e9 / static_cast<double>(n);
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"Cost of each step of a path on a scene"};
  std::string scenePath = NX_SOURCE_DIR "/scenes/thesis.scn";
  int records = 200000;
  app.add_option("scene", scenePath, "Scene file (default: the thesis scene)");
  app.add_option("--records", records, "Surface points to time over (default 200000)")
      ->check(nx::numberIn(1000, 10000000));
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxbench-components"); status >= 0)
    return status;
  try {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    const RenderScene scene = buildRenderScene(loadScene(scenePath));
    const LightSampler lights(scene);
    const Film film(scene.settings.width, scene.settings.height, scene.settings.bands);
    const WavelengthSampler wavelengths(film.tracedMinNm(), film.tracedMaxNm());
    const uint32_t pixels = static_cast<uint32_t>(scene.settings.width * scene.settings.height);

    // Surface points of camera rays (emitters and misses skipped).
    std::vector<Record> in;
    for (uint32_t k = 0; in.size() < static_cast<size_t>(records) && k < 20u * records; ++k) {
      Record r;
      r.pixel = (k * 2654435761u) % pixels;
      const PixelSequence seq(SamplerKind::SobolOwen, r.pixel, 1);
      PixelSampleStream rng(seq, k / pixels);
      r.lambda = wavelengths.sample(rng.next1D());
      const Sample2 j = rng.next2D();
      const uint32_t w = static_cast<uint32_t>(scene.settings.width);
      r.ray = scene.camera.generateRay(static_cast<double>(r.pixel % w) + j.u,
                                       static_cast<double>(r.pixel / w) + j.v);
      if (!scene.geometry->intersect(r.ray, r.hit)) continue;
      if (scene.appearance(r.hit).emission >= 0) continue;
      in.push_back(r);
    }
    if (in.empty()) throw nx::Error(scenePath + ": no camera ray meets a non-emitting surface");
    const size_t n = in.size();
    double sink = 0;
    auto keep = [&](double v) { sink += v; };
    auto u2 = [&](size_t i) {
      return Sample2{static_cast<float>((i * 7919) % 1000) * 1e-3f,
                     static_cast<float>((i * 104729) % 997) / 997.0f};
    };

    std::printf("%-52s %10s\n", "step (one thread, scene's own points)", "ns/call");
    auto row = [](const char* name, double ns) { std::printf("%-52s %10.1f\n", name, ns); };
    row("per sample: wavelengths (kLanes lanes)",
        nsPerCall(n, [&](size_t i) { keep(wavelengths.sample(u2(i).u).lambda[kLanes - 1]); }));
    row("per sample: camera ray", nsPerCall(n, [&](size_t i) {
          keep(scene.camera
                   .generateRay(static_cast<double>(i % 400) + 0.5,
                                static_cast<double>(i % 225) + 0.5)
                   .d.x);
        }));
    row("per sample: sampler, pixel sequence + stream", nsPerCall(n, [&](size_t i) {
          const PixelSequence seq(SamplerKind::SobolOwen, in[i].pixel, 1);
          PixelSampleStream s(seq, static_cast<uint32_t>(i));
          keep(s.next1D());
        }));
    {
      const PixelSequence seq(SamplerKind::SobolOwen, 7, 1);
      row("per draw: sampler pair, Sobol (first 6 pairs)",
          nsPerCall(n, [&](size_t i) {
            PixelSampleStream s(seq, static_cast<uint32_t>(i));
            for (int k = 0; k < 6; ++k) keep(s.next2D().u);
          }) / 6);
      row("per draw: sampler pair, counter-based (later pairs)", nsPerCall(n, [&](size_t i) {
            const Sample2 s =
                seq.pair({static_cast<uint32_t>(i), static_cast<uint32_t>(i) * 3u}, 9);
            keep(s.u);
          }));
    }
    row("per sample: film splat", [&] {
      Film::Pixel p = film.newPixel();
      SampledSpectrum L = SampledSpectrum::filled(0.5f);
      return nsPerCall(n, [&](size_t i) { film.addSample(p, in[i].lambda, L, i & 1); });
    }());
    row("per ray: closest hit (camera rays)", nsPerCall(n, [&](size_t i) {
          SurfaceHit h;
          keep(scene.geometry->intersect(in[i].ray, h) ? h.t : 0.0f);
        }));
    std::vector<LightSample> ls(n);
    std::vector<char> lit(n);
    row("per vertex: light sample", nsPerCall(n, [&](size_t i) {
          lit[i] = lights.sample(in[i].hit.p, u2(i).v, u2(i), in[i].lambda, ls[i]);
        }));
    // Each light alone (its own sampling, without the choice among lights), the first few of
    // each kind: what a vertex pays for aiming at a point light, a sphere, a mesh of n triangles
    // (a binary search over their areas) or the background.
    {
      static const char* kKindNames[] = {"point", "sphere", "mesh", "background", "environment"};
      int shownOfKind[4] = {0, 0, 0, 0};
      LightSample one;
      for (int k = 0; k < lights.count(); ++k) {
        const int kind = static_cast<int>(lights.kind(k));
        if (shownOfKind[kind]++ >= 2) continue;
        char name[96];
        std::snprintf(name, sizeof name, "per vertex: light %d alone (%s%s)", k, kKindNames[kind],
                      kind == static_cast<int>(LightKind::Mesh)
                          ? (", " + std::to_string(lights.triangleCount(k)) + " triangles").c_str()
                          : "");
        row(name, nsPerCall(n, [&](size_t i) {
              keep(lights.sampleLight(k, in[i].hit.p, u2(i).v, u2(i), in[i].lambda, one) ? one.pdf
                                                                                         : 0.0f);
            }));
      }
    }
    row("per ray: shadow ray", nsPerCall(n, [&](size_t i) {
          if (!lit[i]) return;
          keep(scene.geometry->occluded(
              shadowRayTo(in[i].hit.p, in[i].hit.pError, in[i].hit.ng, ls[i])));
        }));
    row("per vertex: reflectance at the lanes", nsPerCall(n, [&](size_t i) {
          const Material& m = scene.materials[scene.appearance(in[i].hit).material];
          keep(evaluate(m.reflectance, in[i].lambda)[0]);
        }));
    row("per vertex: BSDF set-up + sample", nsPerCall(n, [&](size_t i) {
          const Material& m = scene.materials[scene.appearance(in[i].hit).material];
          const SurfaceBsdf bsdf(m, in[i].lambda, SampledSpectrum::filled(0.5f), in[i].hit.ng,
                                 -in[i].ray.d);
          BsdfSample bs;
          keep(bsdf.sample(u2(i).u, u2(i), bs) ? bs.wi.x : 0.0f);
        }));
    size_t fluorescent = 0;
    const PixelSequence sequence(SamplerKind::SobolOwen, 7, 1);
    const double nsShift = nsPerCall(n, [&](size_t i) {
      const Material& m = scene.materials[scene.appearance(in[i].hit).material];
      if (!m.reradiation) return;
      ++fluorescent;
      PixelSampleStream s(sequence, static_cast<uint32_t>(i));
      keep(sampleFluorescentShift(*m.reradiation, in[i].lambda, SampledSpectrum::filled(0.5f), s)
               .excited.lambda[0]);
    });
    if (fluorescent > 0)
      row("per fluorescent vertex: re-radiation choice",
          nsShift * 5 * static_cast<double>(n) / static_cast<double>(fluorescent));

    RenderOptions o;
    o.samples = 8;
    const double seconds = bench::fastestSeconds(2, [&] {
      const RenderOutput r = render(scene, o);
      keep(static_cast<double>(r.stats.rays));
    });
    const RenderOutput r = render(scene, o);
    const double samples = static_cast<double>(r.stats.samples);
    std::printf("\nrender at 8 spp: %.0f ns per sample, %.0f ns per ray, %.2f rays per sample\n",
                seconds * 1e9 / samples, seconds * 1e9 / static_cast<double>(r.stats.rays),
                static_cast<double>(r.stats.rays) / samples);
    if (sink == 12345.678) std::printf(" ");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nxbench-components: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
