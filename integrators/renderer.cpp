#include "integrators/renderer.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <mutex>

#include "core/matrix3.h"
#include "spectra/colour.h"
#include "spectra/tonemap.h"
#include "spectra/wavelength_sampler.h"

namespace nx {

RenderOutput render(const RenderScene& scene, const RenderOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const RenderSettings& settings = scene.settings;
  const SpectralBands bands = options.bands ? *options.bands : settings.bands;
  RenderOutput out{Film(settings.width, settings.height, bands), {}, 0, 0};
  out.samplesPerPixel = options.samples > 0 ? options.samples : settings.samples;
  out.seed = options.seed ? *options.seed : settings.seed;
  const int spp = out.samplesPerPixel;
  const uint32_t seed = out.seed;

  const LightSampler lights(scene);
  const IntegratorContext ctx{&scene, &lights, options.lightSampling,
                              scene.hasFluorescence || options.forceFluorescencePath};
  const WavelengthSampler wavelengths(out.film.minNm(), out.film.maxNm());
  const bool whitted = settings.mode == RenderMode::Rt;

  const int ts = std::max(1, options.tileSize);
  const int tilesX = (settings.width + ts - 1) / ts, tilesY = (settings.height + ts - 1) / ts;
  const int tiles = tilesX * tilesY;
  std::atomic<uint64_t> rays{0}, nonFinite{0};
  std::atomic<int> finished{0};
  std::mutex progressMutex;

  tbb::parallel_for(0, tiles, [&](int tile) {
    const int x0 = (tile % tilesX) * ts, y0 = (tile / tilesX) * ts;
    const int x1 = std::min(x0 + ts, settings.width), y1 = std::min(y0 + ts, settings.height);
    TraceCounters counters;
    uint64_t dropped = 0;
    Film::Pixel pixel = out.film.newPixel();
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) {
        out.film.resetPixel(pixel);
        const uint32_t pixelIndex =
            static_cast<uint32_t>(y) * static_cast<uint32_t>(settings.width) +
            static_cast<uint32_t>(x);
        for (int s = 0; s < spp; ++s) {
          PixelSampleStream rng(options.sampler, pixelIndex, static_cast<uint32_t>(s), seed);
          SampledWavelengths lambda = wavelengths.sample(rng.next1D());
          const Sample2 jitter = rng.next2D();
          const Ray ray = scene.camera.generateRay(static_cast<double>(x) + jitter.u,
                                                   static_cast<double>(y) + jitter.v);
          const SampledSpectrum L = whitted ? traceWhitted(ctx, ray, lambda, rng, counters)
                                            : tracePath(ctx, ray, lambda, rng, counters);
          if (!out.film.addSample(pixel, lambda, L)) ++dropped;
        }
        out.film.store(x, y, pixel);
      }
    }
    rays += counters.rays;
    nonFinite += dropped;
    const int done = ++finished;
    if (options.progress) {
      std::lock_guard<std::mutex> lock(progressMutex);
      options.progress(done, tiles);
    }
  });

  out.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.stats.samples =
      static_cast<uint64_t>(settings.width) * settings.height * static_cast<uint64_t>(spp);
  out.stats.rays = rays;
  out.stats.nonFinite = nonFinite;
  return out;
}

SpectralImage toSpectralImage(const Film& film) {
  SpectralImage img;
  img.width = film.width();
  img.height = film.height();
  img.bands = film.bands();
  const int nb = film.bands().count();
  img.radiance.reserve(static_cast<size_t>(img.width) * img.height * nb);
  img.rgb.reserve(static_cast<size_t>(img.width) * img.height * 3);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      for (int b = 0; b < nb; ++b)
        img.radiance.push_back(static_cast<float>(film.bandMean(x, y, b)));
      const Rgb c = xyzToLinearSrgb(film.xyzMean(x, y));
      img.rgb.push_back(static_cast<float>(std::max(c.r, 0.0)));
      img.rgb.push_back(static_cast<float>(std::max(c.g, 0.0)));
      img.rgb.push_back(static_cast<float>(std::max(c.b, 0.0)));
    }
  return img;
}

std::vector<uint8_t> previewPixels(const Film& film, const Spectrum& white) {
  // Bradford cone response matrix (Lam 1985), von Kries scaling from `white` to D65.
  const Matrix3 bradford{
      {{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};
  const Xyz w = spectrumToXyz(white);
  const Xyz d65 = d65WhiteXyz();
  const Vector3d src = multiply(bradford, {w.x / w.y, 1.0, w.z / w.y});
  const Vector3d dst = multiply(bradford, {d65.x, d65.y, d65.z});
  Matrix3 scale{};
  for (int i = 0; i < 3; ++i) scale[i][i] = dst[i] / src[i];
  Matrix3 adapt{}, tmp{};
  const Matrix3 inv = inverse(bradford);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) tmp[i][j] += scale[i][k] * bradford[k][j];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) adapt[i][j] += inv[i][k] * tmp[k][j];

  std::vector<Rgb> rgb;
  rgb.reserve(static_cast<size_t>(film.width()) * film.height());
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) {
      const Xyz c = film.xyzMean(x, y);
      const Vector3d a = multiply(adapt, {c.x, c.y, c.z});
      rgb.push_back(xyzToLinearSrgb({a[0], a[1], a[2]}));
    }
  return tonemapReinhard(rgb, {});
}

} // namespace nx
