#include "io/part_merge.h"

#include "core/number_text.h"
#include "io/relight_merge.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>

#include "core/error.h"
#include "core/hash.h"
#include "spectra/colour.h"

namespace nx {
namespace {

std::string attribute(const ImagePart& p, const std::string& key) {
  const auto it = p.image.attributes.find(key);
  if (it == p.image.attributes.end())
    throw Error(p.name + ": expected an nxrender part with the attribute " + key + ", found none");
  return it->second;
}

// The adaptive-sampling target of a part ("" for a uniform render).
std::string adaptiveTarget(const ImagePart& p) {
  const auto it = p.image.attributes.find("nxrender.adaptive");
  return it == p.image.attributes.end() ? std::string() : it->second;
}

std::pair<long long, long long> sampleRange(const ImagePart& p) {
  const std::string r = attribute(p, "nxrender.sampleRange");
  const auto colon = r.find(':');
  char* end = nullptr;
  const long long a = std::strtoll(r.c_str(), &end, 10);
  const long long b =
      colon == std::string::npos ? -1 : std::strtoll(r.c_str() + colon + 1, nullptr, 10);
  if (colon == std::string::npos || end != r.c_str() + colon || b <= a || a < 0)
    throw Error(p.name + ": expected a sample range A:B in nxrender.sampleRange, found '" + r +
                "'");
  return {a, b};
}

// The render time of the whole: the parts' times added (CPU-side cost of the image, not the
// wall clock of a farm that ran them at once); none when a part has no valid time.
void setTotalRenderSeconds(SpectralImage& out, const std::vector<ImagePart>& parts) {
  double seconds = 0;
  bool timed = true;
  for (const ImagePart& p : parts) {
    const auto it = p.image.attributes.find("nxrender.renderSeconds");
    const char* end = nullptr;
    const double t = it == p.image.attributes.end() ? NAN : strtodC(it->second.c_str(), &end);
    if (!(t >= 0) || end == nullptr || *end != '\0') timed = false;
    seconds += t;
  }
  if (timed)
    out.attributes["nxrender.renderSeconds"] = std::to_string(seconds);
  else
    out.attributes.erase("nxrender.renderSeconds");
}

std::string rectText(int x0, int y0, int x1, int y1) {
  return std::to_string(x0) + "," + std::to_string(y0) + "," + std::to_string(x1) + "," +
         std::to_string(y1);
}

} // namespace

namespace {

// Parts that share their bands: crops assembled, sample ranges averaged.
SpectralImage mergeSameBands(const std::vector<ImagePart>& parts) {
  const ImagePart& first = parts.front();
  const int width = first.image.displayWidth(), height = first.image.displayHeight();
  const int nb = first.image.bands.count();
  std::vector<std::pair<long long, long long>> ranges;
  for (const ImagePart& p : parts) {
    // The sampler first: parts of one render made before and after the default sampler
    // changed (sobol -> stratified) differ there, and the render key would not say so.
    for (const char* key :
         {"nxrender.sampler", "nxrender.renderKey", "nxrender.seed", "nxrender.bands"})
      if (attribute(p, key) != attribute(first, key))
        throw Error(p.name + ": does not belong with " + first.name + ": its " + key + " is '" +
                    attribute(p, key) + "', not '" + attribute(first, key) + "'" +
                    (std::string(key) == "nxrender.renderKey"
                         ? " (another scene, other data files, other render options or another "
                           "nxrender version)"
                         : ""));
    if (adaptiveTarget(p) != adaptiveTarget(first))
      throw Error(p.name + ": does not belong with " + first.name + ": its adaptive sampling is '" +
                  (adaptiveTarget(p).empty() ? "off" : adaptiveTarget(p)) + "', not '" +
                  (adaptiveTarget(first).empty() ? "off" : adaptiveTarget(first)) + "'");
    if (p.image.displayWidth() != width || p.image.displayHeight() != height)
      throw Error(p.name + ": does not belong with " + first.name + ": its image is " +
                  std::to_string(p.image.displayWidth()) + "x" +
                  std::to_string(p.image.displayHeight()) + ", not " + std::to_string(width) + "x" +
                  std::to_string(height));
    if (p.image.sampleCount.empty() || p.image.xyz.empty())
      throw Error(p.name + ": expected SampleCount and X, Y, Z channels, found none");
    ranges.push_back(sampleRange(p));
    const long long want = ranges.back().second - ranges.back().first;
    // An adaptive part holds up to its range in each pixel (its SampleCount says how many).
    const bool adaptive = !adaptiveTarget(p).empty();
    for (uint32_t c : p.image.sampleCount)
      if (adaptive ? c > want || c == 0 : c != want)
        throw Error(p.name + ": holds " + std::to_string(c) +
                    " samples in some pixels instead of the " + std::to_string(want) +
                    " of its range " + attribute(p, "nxrender.sampleRange") +
                    " (an interrupted render? finish it with nxrender --resume)");
  }
  // Overlaps: two parts covering the same pixels with intersecting sample ranges.
  for (size_t i = 0; i < parts.size(); ++i)
    for (size_t j = i + 1; j < parts.size(); ++j) {
      const SpectralImage &a = parts[i].image, &b = parts[j].image;
      const int x0 = std::max(a.originX, b.originX), y0 = std::max(a.originY, b.originY);
      const int x1 = std::min(a.originX + a.width, b.originX + b.width),
                y1 = std::min(a.originY + a.height, b.originY + b.height);
      if (x0 >= x1 || y0 >= y1) continue;
      if (ranges[i].first < ranges[j].second && ranges[j].first < ranges[i].second)
        throw Error(parts[j].name + ": overlaps " + parts[i].name + ": pixels " +
                    rectText(x0, y0, x1, y1) + " with samples " +
                    attribute(parts[j], "nxrender.sampleRange") + " and " +
                    attribute(parts[i], "nxrender.sampleRange"));
    }

  SpectralImage out;
  out.width = width;
  out.height = height;
  out.bands = first.image.bands;
  out.attributes = first.image.attributes;
  for (const ImagePart& p : parts)
    out.sourceFiles.insert(out.sourceFiles.end(), p.image.sourceFiles.begin(),
                           p.image.sourceFiles.end());
  const size_t pixels = static_cast<size_t>(width) * height;
  std::vector<double> bandSum(pixels * nb, 0.0), xyzSum(pixels * 3, 0.0);
  // Variances of the merged means: sum over parts of (n_k / N)^2 var_k (independent parts).
  const bool variances = std::all_of(parts.begin(), parts.end(), [](const ImagePart& p) {
    return !p.image.bandVariance.empty() && !p.image.yVariance.empty();
  });
  std::vector<double> bandVar(variances ? pixels * nb : 0, 0.0), yVar(variances ? pixels : 0, 0.0);
  // The AOVs, when every part has them: the white reference averaged like the bands; ids and
  // depth (the same in every sample range) taken from a part covering the pixel.
  auto all = [&](auto member) {
    return std::all_of(parts.begin(), parts.end(),
                       [&](const ImagePart& p) { return !(p.image.*member).empty(); });
  };
  const bool white = all(&SpectralImage::white), ids = all(&SpectralImage::objectId),
             depth = all(&SpectralImage::depth);
  std::vector<double> whiteSum(white ? pixels * nb : 0, 0.0);
  // Component layers: every part holds the same ones (the render key names them too), merged
  // like the bands (means weighted by samples, variances by their square).
  auto layerNames = [](const SpectralImage& img) {
    std::string names;
    for (const ImageLayer& l : img.layers) names += (names.empty() ? "" : ",") + l.name;
    return names;
  };
  const size_t nLayers = first.image.layers.size();
  for (const ImagePart& p : parts)
    if (layerNames(p.image) != layerNames(first.image))
      throw Error(p.name + ": does not belong with " + first.name + ": its component layers are '" +
                  layerNames(p.image) + "', not '" + layerNames(first.image) + "'");
  const bool layerVariances = std::all_of(parts.begin(), parts.end(), [](const ImagePart& p) {
    return std::all_of(p.image.layers.begin(), p.image.layers.end(),
                       [](const ImageLayer& l) { return !l.variances.empty(); });
  });
  std::vector<std::vector<double>> layerSum(nLayers, std::vector<double>(pixels * nb, 0.0));
  // Ground-truth layers: the same ones in every part, averaged like the bands.
  auto aovNames = [](const SpectralImage& img) {
    std::string names;
    for (const AovImageLayer& l : img.aovs) names += (names.empty() ? "" : ",") + l.name;
    return names;
  };
  for (const ImagePart& p : parts)
    if (aovNames(p.image) != aovNames(first.image))
      throw Error(p.name + ": does not belong with " + first.name +
                  ": its ground-truth layers are '" + aovNames(p.image) + "', not '" +
                  aovNames(first.image) + "'");
  std::vector<size_t> aovWidth;
  std::vector<std::vector<double>> aovSum;
  for (const AovImageLayer& l : first.image.aovs) {
    aovWidth.push_back(l.values.size() / (static_cast<size_t>(first.image.width) *
                                          static_cast<size_t>(first.image.height)));
    aovSum.emplace_back(pixels * aovWidth.back(), 0.0);
  }
  std::vector<std::vector<double>> layerVar(
      nLayers, std::vector<double>(layerVariances ? pixels * nb : 0, 0.0));
  if (ids) out.objectId.assign(pixels, 0), out.materialId.assign(pixels, 0);
  if (depth) out.depth.assign(pixels, 0.0f);
  std::vector<uint64_t> count(pixels, 0);
  // Which samples cover each pixel: every pixel must end up with the same set (crops of
  // different ranges merged into one image would record a range that no pixel has, and a later
  // resume would repeat samples), however each pixel's set is split among parts (crop A with
  // 0:16 beside crop B as 0:8 + 8:16). The ranges' endpoints cut the samples into elementary
  // intervals; a part stands for the sum of the hashes of the elementary intervals it holds,
  // so a pixel's sum names its set of samples (its parts' ranges are disjoint, checked above).
  std::vector<long long> cuts;
  for (const auto& r : ranges) cuts.push_back(r.first), cuts.push_back(r.second);
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  std::vector<uint64_t> rangeHash;
  for (const auto& r : ranges) {
    uint64_t h = 0;
    for (size_t c = 0; c + 1 < cuts.size(); ++c)
      if (cuts[c] >= r.first && cuts[c + 1] <= r.second)
        h += fnv1a64(std::to_string(cuts[c]) + ":" + std::to_string(cuts[c + 1]));
    rangeHash.push_back(h);
  }
  std::vector<uint64_t> rangeSet(pixels, 0);
  std::vector<int> covering(pixels, 0), owner(pixels, -1);
  for (size_t k = 0; k < parts.size(); ++k) {
    const SpectralImage& p = parts[k].image;
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) {
        const size_t src = static_cast<size_t>(y) * p.width + x;
        const size_t dst = static_cast<size_t>(p.originY + y) * width + (p.originX + x);
        const double n = p.sampleCount[src];
        for (int b = 0; b < nb; ++b)
          bandSum[dst * nb + b] += static_cast<double>(p.radiance[src * nb + b]) * n;
        for (int c = 0; c < 3; ++c)
          xyzSum[dst * 3 + c] += static_cast<double>(p.xyz[src * 3 + c]) * n;
        if (variances) { // weighted by n^2 here, divided by N^2 below
          for (int b = 0; b < nb; ++b)
            bandVar[dst * nb + b] += p.bandVariance[src * nb + b] * n * n;
          yVar[dst] += p.yVariance[src] * n * n;
        }
        if (white)
          for (int b = 0; b < nb; ++b)
            whiteSum[dst * nb + b] += static_cast<double>(p.white[src * nb + b]) * n;
        for (size_t l = 0; l < nLayers; ++l)
          for (int b = 0; b < nb; ++b) {
            layerSum[l][dst * nb + b] += static_cast<double>(p.layers[l].values[src * nb + b]) * n;
            if (layerVariances)
              layerVar[l][dst * nb + b] += p.layers[l].variances[src * nb + b] * n * n;
          }
        for (size_t l = 0; l < aovSum.size(); ++l)
          for (size_t c = 0; c < aovWidth[l]; ++c)
            aovSum[l][dst * aovWidth[l] + c] +=
                static_cast<double>(p.aovs[l].values[src * aovWidth[l] + c]) * n;
        if (ids) out.objectId[dst] = p.objectId[src], out.materialId[dst] = p.materialId[src];
        if (depth) out.depth[dst] = p.depth[src];
        count[dst] += p.sampleCount[src];
        rangeSet[dst] += rangeHash[k];
        ++covering[dst];
        owner[dst] = static_cast<int>(k);
      }
  }
  // Missing regions: pixels with fewer samples than the best-covered pixel (adaptive parts,
  // whose counts differ by design: pixels no part covers).
  const bool adaptive = !adaptiveTarget(first).empty();
  const uint64_t full = *std::max_element(count.begin(), count.end());
  int mx0 = width, my0 = height, mx1 = -1, my1 = -1;
  size_t missing = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (adaptive ? covering[static_cast<size_t>(y) * width + x] == 0
                   : count[static_cast<size_t>(y) * width + x] < full) {
        ++missing;
        mx0 = std::min(mx0, x), my0 = std::min(my0, y), mx1 = std::max(mx1, x + 1),
        my1 = std::max(my1, y + 1);
      }
  if (missing > 0)
    throw Error("missing region: " + std::to_string(missing) + " pixels within " +
                rectText(mx0, my0, mx1, my1) +
                (adaptive
                     ? std::string(" are covered by no part")
                     : " have fewer than the " + std::to_string(full) + " samples of the others") +
                " (a part is missing)");

  // The sample ranges each pixel holds, as text (for the message below).
  auto rangesAt = [&](size_t i) {
    const int x = static_cast<int>(i % width), y = static_cast<int>(i / width);
    std::string text;
    for (size_t k = 0; k < parts.size(); ++k) {
      const SpectralImage& p = parts[k].image;
      if (x >= p.originX && x < p.originX + p.width && y >= p.originY && y < p.originY + p.height)
        text += (text.empty() ? "" : " ") + attribute(parts[k], "nxrender.sampleRange");
    }
    return "pixel " + std::to_string(x) + "," + std::to_string(y) + " holds samples " + text;
  };
  for (size_t i = 1; i < pixels; ++i)
    if (rangeSet[i] != rangeSet[0])
      throw Error("parts cover different sample ranges in different pixels: " + rangesAt(i) + ", " +
                  rangesAt(0) + " (merge crops of the same range, and ranges of the same pixels)");

  out.radiance.resize(pixels * nb);
  out.xyz.resize(pixels * 3);
  out.rgb.resize(pixels * 3);
  out.sampleCount.resize(pixels);
  if (variances) {
    out.bandVariance.resize(pixels * nb);
    out.yVariance.resize(pixels);
  }
  if (white) out.white.resize(pixels * nb);
  for (size_t l = 0; l < nLayers; ++l)
    out.layers.push_back({first.image.layers[l].name, std::vector<float>(pixels * nb),
                          std::vector<float>(layerVariances ? pixels * nb : 0)});
  for (size_t l = 0; l < aovSum.size(); ++l)
    out.aovs.push_back({first.image.aovs[l].name, std::vector<float>(pixels * aovWidth[l])});
  for (size_t i = 0; i < pixels; ++i) {
    out.sampleCount[i] = static_cast<uint32_t>(count[i]);
    if (covering[i] == 1) { // a single part: its values, bit for bit
      const SpectralImage& p = parts[static_cast<size_t>(owner[i])].image;
      const size_t x = i % width, y = i / width;
      const size_t src = (y - p.originY) * p.width + (x - p.originX);
      std::copy_n(&p.radiance[src * nb], nb, &out.radiance[i * nb]);
      std::copy_n(&p.xyz[src * 3], 3, &out.xyz[i * 3]);
      std::copy_n(&p.rgb[src * 3], 3, &out.rgb[i * 3]);
      if (white) std::copy_n(&p.white[src * nb], nb, &out.white[i * nb]);
      for (size_t l = 0; l < aovSum.size(); ++l)
        std::copy_n(&p.aovs[l].values[src * aovWidth[l]], aovWidth[l],
                    &out.aovs[l].values[i * aovWidth[l]]);
      for (size_t l = 0; l < nLayers; ++l) {
        std::copy_n(&p.layers[l].values[src * nb], nb, &out.layers[l].values[i * nb]);
        if (layerVariances)
          std::copy_n(&p.layers[l].variances[src * nb], nb, &out.layers[l].variances[i * nb]);
      }
      if (variances) {
        std::copy_n(&p.bandVariance[src * nb], nb, &out.bandVariance[i * nb]);
        out.yVariance[i] = p.yVariance[src];
      }
      continue;
    }
    const double n = static_cast<double>(count[i]);
    for (int b = 0; b < nb; ++b)
      out.radiance[i * nb + b] = static_cast<float>(bandSum[i * nb + b] / n);
    for (int b = 0; b < nb && white; ++b)
      out.white[i * nb + b] = static_cast<float>(whiteSum[i * nb + b] / n);
    for (size_t l = 0; l < aovSum.size(); ++l)
      for (size_t c = 0; c < aovWidth[l]; ++c)
        out.aovs[l].values[i * aovWidth[l] + c] =
            static_cast<float>(aovSum[l][i * aovWidth[l] + c] / n);
    for (size_t l = 0; l < nLayers; ++l)
      for (int b = 0; b < nb; ++b) {
        out.layers[l].values[i * nb + b] = static_cast<float>(layerSum[l][i * nb + b] / n);
        if (layerVariances)
          out.layers[l].variances[i * nb + b] =
              static_cast<float>(layerVar[l][i * nb + b] / (n * n));
      }
    if (variances) {
      for (int b = 0; b < nb; ++b)
        out.bandVariance[i * nb + b] = static_cast<float>(bandVar[i * nb + b] / (n * n));
      out.yVariance[i] = static_cast<float>(yVar[i] / (n * n));
    }
    const Xyz xyz{xyzSum[i * 3] / n, xyzSum[i * 3 + 1] / n, xyzSum[i * 3 + 2] / n};
    setPixelColour(out, i, xyz);
  }
  out.relight = mergeRelight(parts, width, height, count);
  // The merged sample range: the union, if the ranges are contiguous.
  std::vector<std::pair<long long, long long>> sorted = ranges;
  std::sort(sorted.begin(), sorted.end());
  long long lo = sorted.front().first, hi = sorted.front().second;
  bool contiguous = true;
  for (const auto& r : sorted) {
    if (r.first > hi) contiguous = false;
    hi = std::max(hi, r.second);
  }
  out.attributes["nxrender.sampleRange"] =
      contiguous ? std::to_string(lo) + ":" + std::to_string(hi) : "merged";
  out.attributes["nxrender.mergedParts"] = std::to_string(parts.size());
  setTotalRenderSeconds(out, parts);
  // The merged image's own error estimate (the first part's would describe only that part).
  if (variances) {
    double var = 0, mean = 0;
    for (size_t i = 0; i < pixels; ++i) var += out.yVariance[i], mean += out.xyz[i * 3 + 1];
    const double n = static_cast<double>(pixels);
    out.attributes["nxrender.estimatedRelativeError"] =
        std::to_string(mean > 0 ? std::sqrt(var / n) / (mean / n) : INFINITY);
  } else {
    out.attributes.erase("nxrender.estimatedRelativeError");
  }
  return out;
}

// Images of the same scene, seed, pixels and samples with disjoint bands: one image with every
// band, ordered by centroid. XYZ, RGB and Variance.Y come from the first image (each image
// estimated them from its own wavelengths; they are not averaged, since the images share
// their random numbers and are not independent).
SpectralImage stitchBands(const std::vector<ImagePart>& images) {
  const ImagePart& first = images.front();
  for (const ImagePart& p : images)
    if (p.image.relight.present())
      throw Error(p.name + ": a relightable render's band ranges cannot be stitched (its "
                           "transport's pattern is the bands'): render the bands together, "
                           "split by --crop or --spp-range instead");
  const SpectralImage& a = first.image;
  const size_t pixels = static_cast<size_t>(a.width) * static_cast<size_t>(a.height);
  struct Source {
    size_t image;
    int band;
  };
  std::vector<SensorChannel> channels;
  std::vector<Source> sources;
  std::map<std::string, std::string> layerOwner;
  for (size_t k = 0; k < images.size(); ++k) {
    const ImagePart& p = images[k];
    for (const char* key :
         {"nxrender.sampler", "nxrender.renderKey", "nxrender.seed", "nxrender.sampleRange"})
      if (attribute(p, key) != attribute(first, key))
        throw Error(p.name + ": cannot be stitched with " + first.name + " (other bands): its " +
                    key + " is '" + attribute(p, key) + "', not '" + attribute(first, key) +
                    "' (band ranges are stitched from renders of the same scene, options, seed "
                    "and samples)");
    if (p.image.width != a.width || p.image.height != a.height || p.image.originX != a.originX ||
        p.image.originY != a.originY || p.image.displayWidth() != a.displayWidth() ||
        p.image.displayHeight() != a.displayHeight())
      throw Error(p.name + ": cannot be stitched with " + first.name +
                  ": it covers other pixels (stitch whole images of the same size)");
    if (p.image.sampleCount != a.sampleCount)
      throw Error(p.name + ": cannot be stitched with " + first.name +
                  ": its pixels hold other sample counts");
    const Sensor& s = p.image.bands;
    for (int b = 0; b < s.count(); ++b) {
      const std::string layer = spectralChannelName(s.channelNm(b));
      if (auto [it, fresh] = layerOwner.emplace(layer, p.name); !fresh)
        throw Error(p.name + ": cannot be stitched with " + it->second + ": both hold the band " +
                    layer + " (stitch renders of disjoint bands)");
      channels.push_back(s.channel(b));
      sources.push_back({k, b});
    }
  }
  // Order by centroid.
  std::vector<size_t> order(channels.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::vector<double> centroids;
  for (const Source& src : sources)
    centroids.push_back(images[src.image].image.bands.centroid(src.band));
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t x, size_t y) { return centroids[x] < centroids[y]; });
  std::vector<SensorChannel> sortedChannels;
  std::vector<Source> sortedSources;
  for (size_t i : order) sortedChannels.push_back(channels[i]), sortedSources.push_back(sources[i]);

  SpectralImage out = a;
  for (size_t k = 1; k < images.size(); ++k)
    out.sourceFiles.insert(out.sourceFiles.end(), images[k].image.sourceFiles.begin(),
                           images[k].image.sourceFiles.end());
  out.bands = Sensor::fromChannels(std::move(sortedChannels), "stitched bands");
  try {
    out.attributes["nxrender.bands"] = out.bands.toString();
  } catch (const Error&) {
    throw Error("cannot stitch bands of different kinds (boxes, Gaussians and measured "
                "responses): render them with one kind of sensor");
  }
  const size_t nb = sortedSources.size();
  const bool variances = std::all_of(images.begin(), images.end(), [](const ImagePart& p) {
    return !p.image.bandVariance.empty();
  });
  const bool white = std::all_of(images.begin(), images.end(),
                                 [](const ImagePart& p) { return !p.image.white.empty(); });
  out.radiance.assign(pixels * nb, 0.0f);
  out.bandVariance.assign(variances ? pixels * nb : 0, 0.0f);
  out.white.assign(white ? pixels * nb : 0, 0.0f);
  for (const ImagePart& p : images)
    if (!p.image.aovs.empty())
      throw Error(p.name +
                  ": cannot be stitched with other band sets: it holds ground-truth "
                  "layers (--aov " +
                  p.image.aovs.front().name + "); render them with one band set");
  // Component layers: the same ones in every image, stitched like the bands.
  for (const ImagePart& p : images) {
    bool same = p.image.layers.size() == a.layers.size();
    for (size_t l = 0; same && l < a.layers.size(); ++l)
      same = p.image.layers[l].name == a.layers[l].name &&
             p.image.layers[l].variances.empty() == a.layers[l].variances.empty();
    if (!same)
      throw Error(p.name + ": cannot be stitched with " + first.name +
                  ": it holds other component layers (render every band range with the same "
                  "--aov)");
  }
  for (ImageLayer& l : out.layers) {
    l.values.assign(pixels * nb, 0.0f);
    if (!l.variances.empty()) l.variances.assign(pixels * nb, 0.0f);
  }
  for (size_t c = 0; c < nb; ++c) {
    const SpectralImage& src = images[sortedSources[c].image].image;
    const size_t srcBands = static_cast<size_t>(src.bands.count()),
                 b = static_cast<size_t>(sortedSources[c].band);
    for (size_t i = 0; i < pixels; ++i) {
      out.radiance[i * nb + c] = src.radiance[i * srcBands + b];
      if (variances) out.bandVariance[i * nb + c] = src.bandVariance[i * srcBands + b];
      if (white) out.white[i * nb + c] = src.white[i * srcBands + b];
      for (size_t l = 0; l < out.layers.size(); ++l) {
        out.layers[l].values[i * nb + c] = src.layers[l].values[i * srcBands + b];
        if (!out.layers[l].variances.empty())
          out.layers[l].variances[i * nb + c] = src.layers[l].variances[i * srcBands + b];
      }
    }
  }
  setTotalRenderSeconds(out, images);
  out.attributes["nxrender.stitchedBandSets"] = std::to_string(images.size());
  return out;
}

} // namespace

SpectralImage mergeParts(const std::vector<ImagePart>& parts) {
  if (parts.empty()) throw Error("nothing to merge");
  // Parts are grouped by their bands; each group is merged, then the groups are stitched.
  std::vector<std::string> keys;
  std::vector<std::vector<ImagePart>> groups;
  for (const ImagePart& p : parts) {
    const std::string key = attribute(p, "nxrender.bands");
    const auto it = std::find(keys.begin(), keys.end(), key);
    if (it == keys.end()) {
      keys.push_back(key);
      groups.emplace_back();
    }
    groups[static_cast<size_t>(std::find(keys.begin(), keys.end(), key) - keys.begin())].push_back(
        p);
  }
  if (groups.size() == 1) return mergeSameBands(parts);
  std::vector<ImagePart> merged;
  for (const auto& g : groups) {
    std::string names;
    for (const ImagePart& p : g) names += (names.empty() ? "" : "+") + p.name;
    try {
      merged.push_back({names, mergeSameBands(g)});
    } catch (const Error& e) {
      throw Error("the parts with bands " + g.front().image.bands.summary() + " (" + names +
                  "): " + e.what());
    }
  }
  return stitchBands(merged);
}

} // namespace nx
