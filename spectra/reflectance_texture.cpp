#include "spectra/reflectance_texture.h"
#include "core/cell_index.h"

#include "core/texel_grid.h"

#include <algorithm>
#include <cmath>

#include "spectra/colorchecker.h"
#include "spectra/spectrum.h"

namespace nx {

std::shared_ptr<const ReflectanceTexture>
ReflectanceTexture::spectralImage(int width, int height, std::vector<double> centroidsNm,
                                  std::vector<float> values, bool holdEnds) {
  auto t = std::make_shared<ReflectanceTexture>();
  t->kind_ = Kind::Image;
  t->holdEnds_ = holdEnds;
  t->width_ = width;
  t->height_ = height;
  t->centroids_ = std::move(centroidsNm);
  t->values_ = std::move(values);
  return t;
}

std::shared_ptr<const ReflectanceTexture>
ReflectanceTexture::sigmoidImage(int width, int height, std::vector<float> coefficients) {
  auto t = std::make_shared<ReflectanceTexture>();
  t->kind_ = Kind::Sigmoid;
  t->width_ = width;
  t->height_ = height;
  t->values_ = std::move(coefficients);
  return t;
}

std::shared_ptr<const ReflectanceTexture> ReflectanceTexture::colorChecker(bool holdEnds) {
  auto t = std::make_shared<ReflectanceTexture>();
  t->kind_ = Kind::Chart;
  t->width_ = kColorCheckerColumns;
  t->height_ = kColorCheckerRows;
  t->holdEnds_ = holdEnds;
  for (int i = 0; i < kColorCheckerColumns * kColorCheckerRows; ++i) {
    const Spectrum& p = colorCheckerPatch(i);
    TabulatedSpectrum table = std::get<TabulatedSpectrum>(p.kind());
    table.holdEnds = holdEnds;
    t->patches_.emplace_back(std::move(table), p.scale());
  }
  return t;
}

std::optional<std::pair<double, double>> ReflectanceTexture::dataRangeNm() const {
  switch (kind_) {
  case Kind::Image:
    return std::pair{centroids_.front(), centroids_.back()};
  case Kind::Chart: {
    const auto& table = std::get<TabulatedSpectrum>(colorCheckerPatch(0).kind());
    return std::pair{table.nm.front(), table.nm.back()};
  }
  case Kind::Sigmoid:
    break;
  }
  return std::nullopt;
}

SampledSpectrum ReflectanceTexture::evaluate(float u, float v,
                                             const SampledWavelengths& lambda) const {
  switch (kind_) {
  case Kind::Image:
    return imageAt(u, v, lambda);
  case Kind::Sigmoid:
    return sigmoidAt(u, v, lambda);
  case Kind::Chart:
    break;
  }
  return chartAt(u, v, lambda);
}

SampledSpectrum ReflectanceTexture::chartAt(float u, float v,
                                            const SampledWavelengths& lambda) const {
  const float x = std::clamp(u, 0.0f, 1.0f) * kColorCheckerColumns;
  const float y = (1 - std::clamp(v, 0.0f, 1.0f)) * kColorCheckerRows;
  const int col = cellIndex(x, kColorCheckerColumns);
  const int row = cellIndex(y, kColorCheckerRows);
  const float fx = x - static_cast<float>(col), fy = y - static_cast<float>(row);
  const float margin = 0.5f * (1 - kColorCheckerPatchFraction);
  if (fx < margin || fx > 1 - margin || fy < margin || fy > 1 - margin)
    return SampledSpectrum::filled(kColorCheckerFrame);
  SampledSpectrum out;
  patches_[static_cast<size_t>(row * kColorCheckerColumns + col)].evaluate(lambda, out);
  return out;
}

ReflectanceTexture::Bilinear ReflectanceTexture::bilinear(float u, float v) const {
  const BilinearTexels b = bilinearTexels(u, v, width_, height_);
  return {{b.texel[0], b.texel[1], b.texel[2], b.texel[3]},
          {b.weight[0], b.weight[1], b.weight[2], b.weight[3]}};
}

SampledSpectrum ReflectanceTexture::imageAt(float u, float v,
                                            const SampledWavelengths& lambda) const {
  const Bilinear b = bilinear(u, v);
  const size_t bands = centroids_.size();
  auto texel = [&](size_t band) {
    float sum = 0;
    for (int k = 0; k < 4; ++k) sum += b.weight[k] * values_[b.texel[k] * bands + band];
    return sum;
  };
  SampledSpectrum out;
  for (int i = 0; i < kLanes; ++i) {
    const double nm = lambda.lambda[i];
    // Linear between the centroids around nm; beyond them the end bands held, or 0.
    const size_t hi = static_cast<size_t>(
        std::upper_bound(centroids_.begin(), centroids_.end(), nm) - centroids_.begin());
    if (nm < centroids_.front() || nm > centroids_.back()) {
      out[i] = holdEnds_ ? texel(hi == 0 ? 0 : bands - 1) : 0.0f;
    } else if (hi == bands) { // at the last centroid
      out[i] = texel(bands - 1);
    } else {
      const double w = (nm - centroids_[hi - 1]) / (centroids_[hi] - centroids_[hi - 1]);
      out[i] = static_cast<float>((1 - w) * texel(hi - 1) + w * texel(hi));
    }
  }
  return out;
}

SampledSpectrum ReflectanceTexture::sigmoidAt(float u, float v,
                                              const SampledWavelengths& lambda) const {
  const Bilinear b = bilinear(u, v);
  SampledSpectrum out;
  for (int i = 0; i < kLanes; ++i) {
    // The texels' spectra (Jakob & Hanika's sigmoid of a quadratic), weighted bilinearly.
    const float x = static_cast<float>((lambda.lambda[i] - kSigmoidStartNm) / kSigmoidSpanNm);
    float sum = 0;
    for (int k = 0; k < 4; ++k) {
      const float* c = &values_[b.texel[k] * 3];
      // |p| capped where S(p) is within 1e-18 of 0 or 1, so that p * p cannot overflow.
      const float p = std::clamp((c[0] * x + c[1]) * x + c[2], -1e9f, 1e9f);
      sum += b.weight[k] * (0.5f + 0.5f * p / std::sqrt(1.0f + p * p));
    }
    out[i] = sum;
  }
  return out;
}

} // namespace nx
