#include "integrators/aov_layers.h"

#include <algorithm>
#include <cmath>

#include "accel/geometry_scene.h"
#include "core/error.h"
#include "integrators/materials/bsdf.h"
#include "integrators/render_scene.h"

namespace nx {
namespace {

// kNodes wavelengths per band at the quantiles (j + 1/2) / kNodes of its response, found on a
// 0.05 nm grid over its support.
std::vector<float> bandNodes(const Sensor& bands, int perBand) {
  std::vector<float> out;
  for (int b = 0; b < bands.count(); ++b) {
    const SensorChannel& c = bands.channel(b);
    const double step = 0.05;
    std::vector<double> cdf{0.0};
    for (double nm = c.lo; nm < c.hi; nm += step)
      cdf.push_back(cdf.back() + std::max(0.0, c(nm + step / 2)) * step);
    const double total = cdf.back();
    for (int j = 0; j < perBand; ++j) {
      const double target = (j + 0.5) / perBand * total;
      const size_t k =
          static_cast<size_t>(std::lower_bound(cdf.begin(), cdf.end(), target) - cdf.begin());
      double nm = c.centreNm;
      if (total > 0 && k > 0 && k < cdf.size()) {
        const double t = (target - cdf[k - 1]) / std::max(cdf[k] - cdf[k - 1], 1e-300);
        nm = c.lo + (static_cast<double>(k - 1) + t) * step;
      }
      out.push_back(static_cast<float>(nm));
    }
  }
  return out;
}

} // namespace

AovEvaluator::AovEvaluator(const RenderScene& scene, std::vector<AovKind> kinds,
                           const Sensor& bands)
    : scene_(scene), bands_(bands.count()) {
  for (AovKind k : kAovKinds) {
    const auto n = std::count(kinds.begin(), kinds.end(), k);
    if (n > 1) throw Error(std::string("--aov: '") + aovName(k) + "' given twice");
    if (n == 1) kinds_.push_back(k);
  }
  for (AovKind k : kinds_) channels_ += static_cast<int>(aovChannelNames(k, bands).size());
  nodes_ = bandNodes(bands, kNodes);
  materials_.resize(scene.materials.size());
  constexpr int n = ReradiationMatrix::kBins;
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    const Material& material = scene.materials[m];
    const ReradiationMatrix* r = material.reradiation.get();
    MaterialBands& mb = materials_[m];
    if (albedoIsReflectance(material) && !material.texture) {
      mb.reflectance = bandMeans([&](const SampledWavelengths& l) {
        SampledSpectrum rho;
        material.reflectance.evaluate(l, rho);
        return rho;
      });
      if (r)
        mb.elastic = bandMeans([&](const SampledWavelengths& l) {
          SampledSpectrum rho;
          material.reflectance.evaluate(l, rho);
          for (int i = 0; i < kLanes; ++i)
            if (const int bin = ReradiationMatrix::binOf(l.lambda[static_cast<size_t>(i)]);
                bin >= 0)
              rho[i] = static_cast<float>(r->elastic(bin, rho[i]));
          return rho;
        });
    }
    if (!r || offset(AovKind::Fluorescence) < 0) continue;
    std::vector<float> absorption(n, 0.0f), emission(n, 0.0f);
    double emitted = 0;
    for (int o = 0; o < n; ++o) emitted += r->columnSum(o);
    for (int i = 0; i < n; ++i) {
      double photons = 0;
      for (int o = i + 1; o < n; ++o)
        photons += (*r)(i, o) * ReradiationMatrix::centre(o) / ReradiationMatrix::centre(i);
      absorption[static_cast<size_t>(i)] = static_cast<float>(photons);
      if (emitted > 0)
        emission[static_cast<size_t>(i)] =
            static_cast<float>(r->columnSum(i) / (emitted * ReradiationMatrix::kBinNm));
    }
    auto perBin = [](const std::vector<float>& v) {
      return [&v](const SampledWavelengths& l) {
        SampledSpectrum out = SampledSpectrum::filled(0.0f);
        for (int i = 0; i < kLanes; ++i)
          if (const int bin = ReradiationMatrix::binOf(l.lambda[static_cast<size_t>(i)]); bin >= 0)
            out[i] = v[static_cast<size_t>(bin)];
        return out;
      };
    };
    mb.absorption = bandMeans(perBin(absorption));
    mb.emission = bandMeans(perBin(emission));
  }
}

SampledWavelengths AovEvaluator::nodeLanes(int first) const {
  const int total = bands_ * kNodes;
  SampledWavelengths lambda;
  for (int i = 0; i < kLanes; ++i) {
    lambda.lambda[static_cast<size_t>(i)] =
        nodes_[static_cast<size_t>(std::min(first + i, total - 1))];
    lambda.pdf[static_cast<size_t>(i)] = 1;
  }
  return lambda;
}

template <class F>
std::vector<float> AovEvaluator::bandMeans(F&& lanes) const {
  std::vector<float> out(static_cast<size_t>(bands_), 0.0f);
  const int total = bands_ * kNodes;
  for (int first = 0; first < total; first += kLanes) {
    const SampledWavelengths lambda = nodeLanes(first);
    const SampledSpectrum v = lanes(lambda);
    for (int i = 0; i < kLanes && first + i < total; ++i)
      out[static_cast<size_t>((first + i) / kNodes)] += v[i] / kNodes;
  }
  return out;
}

int AovEvaluator::offset(AovKind k) const {
  int at = 0;
  for (AovKind kept : kinds_) {
    if (kept == k) return at;
    at += aovChannelCount(kept, bands_);
  }
  return -1;
}

void AovEvaluator::evaluate(const Ray& ray, PixelSampleStream& rng, float* out) const {
  std::fill(out, out + channels_, 0.0f);
  SurfaceHit hit;
  if (!scene_.geometry->intersect(ray, hit)) return;
  auto put3 = [](float* at, const Vec3& v) { at[0] = v.x, at[1] = v.y, at[2] = v.z; };
  // Each kept layer's value in its channels (in kAovKinds order; a layer added to
  // NX_AOV_LAYERS is a compile error here until it is evaluated).
  float* at = out;
  for (AovKind k : kinds_) {
    switch (k) {
    case AovKind::Normals:
      put3(at, hit.ns);
      break;
    case AovKind::GeometricNormals:
      put3(at, hit.ng);
      break;
    case AovKind::Position:
      put3(at, hit.p);
      break;
    case AovKind::Uv:
      surfaceUv(hit);
      at[0] = hit.u, at[1] = hit.v;
      break;
    case AovKind::Albedo:
      albedo(hit, ray, rng, at);
      break;
    case AovKind::Fluorescence:
      fluorescence(hit, at);
      break;
    }
    at += aovChannelCount(k, bands_);
  }
}

void AovEvaluator::albedo(const SurfaceHit& h, const Ray& ray, PixelSampleStream& rng,
                          float* out) const {
  SurfaceHit hit = h;
  const ShapeAppearance& app = scene_.appearance(hit);
  const Material& material = scene_.materials[app.material];
  const float k = scene_.concentrationAt(material, hit);
  const Vec3 wo = -ray.d;
  // Matte and the mirror mixtures reflect their reflectance in all: rho = (1 - r) rho + r rho.
  const bool exact = albedoIsReflectance(material);
  const MaterialBands& mb = materials_[app.material];
  if (exact && !mb.reflectance.empty()) { // (untextured: the same everywhere)
    if (dot(wo, hit.ng) * dot(wo, hit.ns) <= 0) return;
    for (int b = 0; b < bands_; ++b)
      out[b] = mb.elastic.empty() ? mb.reflectance[static_cast<size_t>(b)]
                                  : (1 - k) * mb.reflectance[static_cast<size_t>(b)] +
                                        k * mb.elastic[static_cast<size_t>(b)];
    return;
  }
  const int total = bands_ * kNodes;
  for (int first = 0; first < total; first += kLanes) {
    const SampledWavelengths lambda = nodeLanes(first);
    SampledSpectrum rho = scene_.reflectanceAt(material, hit, lambda);
    // A dye reflects its elastic part (fluorescence is the other layer): (1 - k) rho + k D.
    if (const ReradiationMatrix* r = material.reradiation.get())
      for (int i = 0; i < kLanes; ++i) {
        const int bin = ReradiationMatrix::binOf(lambda.lambda[static_cast<size_t>(i)]);
        if (bin >= 0) rho[i] = (1 - k) * rho[i] + k * static_cast<float>(r->elastic(bin, rho[i]));
      }
    SampledSpectrum a = rho;
    if (!exact) {
      SurfaceBsdf bsdf(material, lambda, rho, hit.ng, hit.ns, wo, TransportMode::Energy);
      bsdf.orient(hit.dpdu);
      BsdfSample bs;
      const float uLobe = rng.next1D();
      const Sample2 u = rng.next2D();
      a = bsdf.sample(uLobe, u, bs) ? bs.weight : SampledSpectrum::filled(0.0f);
      if (bs.terminateSecondary) // (a dispersive refraction: the hero lane's alone)
        for (int i = 1; i < kLanes; ++i) {
          SampledWavelengths one = lambda;
          std::swap(one.lambda[0], one.lambda[static_cast<size_t>(i)]);
          SampledSpectrum rhoOne = rho;
          std::swap(rhoOne[0], rhoOne[i]);
          SurfaceBsdf b1(material, one, rhoOne, hit.ng, hit.ns, wo, TransportMode::Energy);
          b1.orient(hit.dpdu);
          BsdfSample s1;
          a[i] = b1.sample(uLobe, u, s1) ? s1.weight[0] : 0.0f;
        }
    } else if (dot(wo, hit.ng) * dot(wo, hit.ns) <= 0) {
      a = SampledSpectrum::filled(0.0f);
    }
    for (int i = 0; i < kLanes && first + i < total; ++i)
      out[(first + i) / kNodes] += a[i] / kNodes;
  }
}

void AovEvaluator::fluorescence(SurfaceHit& hit, float* out) const {
  const ShapeAppearance& app = scene_.appearance(hit);
  const MaterialBands& mb = materials_[app.material];
  if (mb.absorption.empty()) return;
  const float k = scene_.concentrationAt(scene_.materials[app.material], hit);
  for (int b = 0; b < bands_; ++b) {
    out[b] = k * mb.absorption[static_cast<size_t>(b)];
    out[bands_ + b] = mb.emission[static_cast<size_t>(b)];
  }
}

} // namespace nx
