#include "io/texture_reader.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/error.h"
#include "core/text_table.h"
#include "io/spectral_exr.h"
#include "io/srgb_image.h"
#include "spectra/sigmoid_table.h"

namespace nx {
namespace {

bool isExrPath(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".exr";
}

std::shared_ptr<const ReflectanceTexture> srgbTexture(const std::string& bytes,
                                                      const std::string& path) {
  const LinearSrgbImage img = decodeSrgbImage(bytes, path);
  const size_t texels = static_cast<size_t>(img.width) * static_cast<size_t>(img.height);
  std::vector<float> coefficients(texels * 3);
  const SigmoidTable& table = srgbSigmoidTable();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, texels),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t t = r.begin(); t != r.end(); ++t) {
                        const float* c = &img.rgb[t * 3];
                        const SigmoidCoefficients k = table.lookup({c[0], c[1], c[2]});
                        for (int a = 0; a < 3; ++a)
                          coefficients[t * 3 + a] = static_cast<float>(k[a]);
                      }
                    });
  return ReflectanceTexture::sigmoidImage(img.width, img.height, std::move(coefficients));
}

std::shared_ptr<const ReflectanceTexture> spectralTexture(const std::string& path, bool holdEnds) {
  const SpectralImage img = readSpectralExr(path);
  const int nb = img.bands.count();
  std::vector<int> order(static_cast<size_t>(nb));
  for (int b = 0; b < nb; ++b) order[static_cast<size_t>(b)] = b;
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return img.bands.centroid(a) < img.bands.centroid(b); });
  std::vector<double> centroids;
  for (int b : order) centroids.push_back(img.bands.centroid(b));
  std::vector<float> values(img.radiance.size());
  const size_t pixels = static_cast<size_t>(img.width) * img.height;
  for (size_t p = 0; p < pixels; ++p)
    for (size_t k = 0; k < order.size(); ++k) {
      const float v = img.radiance[p * static_cast<size_t>(nb) + static_cast<size_t>(order[k])];
      if (!(v >= 0 && v <= 1))
        throw Error(path + ": expected reflectances within [0, 1], found " + numberText(v) +
                    " at pixel " + std::to_string(p % img.width) + "," +
                    std::to_string(p / img.width) + " in band " + numberText(centroids[k]) + " nm");
      values[p * order.size() + k] = v;
    }
  return ReflectanceTexture::spectralImage(img.width, img.height, std::move(centroids),
                                           std::move(values), holdEnds);
}

} // namespace

std::shared_ptr<const ReflectanceTexture>
readReflectanceTexture(const std::string& path, const std::string& bytes, bool holdEnds) {
  return isExrPath(path) ? spectralTexture(path, holdEnds) : srgbTexture(bytes, path);
}

} // namespace nx
