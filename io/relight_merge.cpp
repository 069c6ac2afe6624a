#include "io/relight_merge.h"

#include "core/error.h"

namespace nx {

RelightLayers mergeRelight(const std::vector<ImagePart>& parts, int width, int height,
                           const std::vector<uint64_t>& count) {
  const ImagePart& first = parts.front();
  const RelightLayers& a = first.image.relight;
  for (const ImagePart& p : parts) {
    const RelightLayers& r = p.image.relight;
    const bool same = r.present() == a.present() && r.sources == a.sources &&
                      r.grid.stepNm == a.grid.stepNm && r.spectra == a.spectra &&
                      r.guides == a.guides && r.split == a.split &&
                      r.entries.size() == a.entries.size() &&
                      std::equal(r.entries.begin(), r.entries.end(), a.entries.begin(), sameEntry);
    if (!same)
      throw Error(
          p.name + ": does not belong with " + first.name + ": their relight transports differ (" +
          (r.present() ? std::to_string(r.sources.size()) + " groups, " +
                             std::to_string(r.entries.size()) + " entries"
                       : std::string("none")) +
          " against " +
          (a.present() ? std::to_string(a.sources.size()) + " groups, " +
                             std::to_string(a.entries.size()) + " entries"
                       : std::string("none")) +
          "; render every part with the same --relightable, --relight-step and --relight-for)");
  }
  RelightLayers out;
  if (!a.present()) return out;
  out.grid = a.grid;
  out.entries = a.entries;
  out.split = a.split;
  out.sources = a.sources;
  out.spectra = a.spectra;
  out.guides = a.guides;
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
  const size_t planes = a.sources.size() * a.entries.size();
  std::vector<double> sum(planes * pixels, 0.0), half(planes * pixels, 0.0);
  for (const ImagePart& part : parts) {
    const SpectralImage& p = part.image;
    const size_t partPixels = static_cast<size_t>(p.width) * static_cast<size_t>(p.height);
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) {
        const size_t src = static_cast<size_t>(y) * p.width + x;
        const size_t dst = static_cast<size_t>(p.originY + y) * width + (p.originX + x);
        const double n = p.sampleCount[src];
        for (size_t k = 0; k < planes; ++k) {
          sum[k * pixels + dst] += static_cast<double>(p.relight.values[k * partPixels + src]) * n;
          half[k * pixels + dst] +=
              static_cast<double>(p.relight.halfDifferences[k * partPixels + src]) * n;
        }
      }
  }
  // (v n) / n is v again in double for counts below 2^29: one part's values stay bit for bit.
  out.values.resize(planes * pixels);
  out.halfDifferences.resize(planes * pixels);
  for (size_t k = 0; k < planes; ++k)
    for (size_t i = 0; i < pixels; ++i) {
      const double n = static_cast<double>(count[i]);
      out.values[k * pixels + i] = n > 0 ? static_cast<float>(sum[k * pixels + i] / n) : 0.0f;
      out.halfDifferences[k * pixels + i] =
          n > 0 ? static_cast<float>(half[k * pixels + i] / n) : 0.0f;
    }
  return out;
}

} // namespace nx
