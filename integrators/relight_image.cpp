#include "integrators/relight_image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <tbb/parallel_for.h>

#include "core/error.h"
#include "core/hash.h"
#include "integrators/relight_pattern.h"
#include "integrators/relight_targets.h"
#include "spectra/band_colour.h"
#include "spectra/colour.h"
#include "spectra/illuminants.h"
#include "spectra/spectrum_bounds.h"

namespace nx {
namespace {

void requireTransport(const SpectralImage& image) {
  if (!image.relight.present())
    throw Error("expected a relightable image (rendered with --relightable), found one without "
                "relight channels");
}

} // namespace

std::vector<size_t> relightSourcesOf(const SpectralImage& image, const std::string& group) {
  requireTransport(image);
  const RelightLayers& rl = image.relight;
  std::vector<size_t> out;
  for (size_t s = 0; s < rl.sources.size(); ++s)
    if (rl.groupOf(s) == group) out.push_back(s);
  if (out.empty()) {
    std::string list;
    for (const std::string& n : rl.groups()) list += (list.empty() ? "" : ", ") + n;
    throw Error("expected a light group of the image (" + list + "), found '" + group + "'");
  }
  return out;
}

GroupSpectrum groupSpectrum(const SpectralImage& image, const std::string& group, const Spectrum& s,
                            double tableLoNm, double tableHiNm, const std::string& source,
                            std::vector<std::string>& warnings) {
  const std::vector<size_t> ofGroup = relightSourcesOf(image, group);
  const RelightLayers& rl = image.relight;
  // The scene's own check of an emission (blackbody:100 and values beyond 1e12 overflowed
  // only at the write).
  if (const std::string problem = emissionProblem(s); !problem.empty())
    throw Error(source + ": " + problem);
  GroupSpectrum out{group, binAverages(s, rl.grid), source};
  for (size_t j = 0; j < out.binned.size(); ++j)
    if (!(out.binned[j] >= 0 && std::isfinite(out.binned[j])))
      throw Error(source + ": expected an emission spectrum of finite values >= 0, found " +
                  numberText(out.binned[j]) + " on average over " +
                  numberText(rl.grid.lo(static_cast<int>(j))) + "-" +
                  numberText(rl.grid.lo(static_cast<int>(j) + 1)) + " nm");
  // The bins the group's transport reaches: where a table that ends early is 0.
  const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  int lo = rl.grid.bins, hi = -1;
  for (const size_t g : ofGroup)
    for (size_t e = 0; e < rl.size(); ++e) {
      const float* v = rl.values.data() + (g * rl.size() + e) * pixels;
      if (std::any_of(v, v + pixels, [](float x) { return x != 0; })) {
        lo = std::min(lo, rl.entries[e].bin);
        hi = std::max(hi, rl.entries[e].bin);
      }
    }
  if (hi >= lo && (tableLoNm > rl.grid.lo(lo) || tableHiNm < rl.grid.lo(hi + 1)))
    warnings.push_back(source + ": warning: tabulated over " + numberText(tableLoNm) + "-" +
                       numberText(tableHiNm) + " nm and the transport of light group '" + group +
                       "' reaches " + numberText(rl.grid.lo(lo)) + "-" +
                       numberText(rl.grid.lo(hi + 1)) +
                       " nm: it is 0 beyond its table, as a render would take it");
  // A spectrum much narrower than what the render drew: the relit image is noisier than a
  // direct render's (docs/relighting.md, "Relighting targets").
  const RelitNoise noise = relitNoiseFactor(image, ofGroup, out.binned);
  if (noise.factor >= kRelitNoiseWarning) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "%.1fx as noisy (standard deviation) as a direct render under it at equal "
                  "samples, in band %s nm (%.0f%% of it fluoresced light)",
                  noise.factor, numberText(image.bands.centroid(noise.band)).c_str(),
                  100 * noise.fluorescedShare);
    warnings.push_back(
        source + ": warning: light group '" + group +
        "' relit to a spectrum much narrower than what the render drew for: expected about " +
        text +
        (rl.guides.empty() ? "; render with --relight-for " + group + "=" + source +
                                 " (Python relight_for=) to draw for it"
                           : " (the render drew for other --relight-for targets: add it to them)"));
  }
  return out;
}

GroupSpectrum groupSpectrumFromText(const SpectralImage& image, const std::string& group,
                                    const std::string& text, std::vector<std::string>& warnings) {
  relightSourcesOf(image, group); // an unknown group before reading a file
  const TextSpectrum t = spectrumFromText(text);
  return groupSpectrum(image, group, t.spectrum, t.loNm, t.hiNm, text, warnings);
}

SpectralImage relightImage(const SpectralImage& image, const std::vector<GroupSpectrum>& spectra) {
  requireTransport(image);
  const RelightLayers& rl = image.relight;
  // Each source's spectrum: its group's new one, else the one it was rendered with.
  std::vector<const std::vector<double>*> use;
  for (const std::vector<double>& s : rl.spectra) use.push_back(&s);
  std::vector<bool> given(rl.sources.size(), false);
  std::string relit;
  for (const GroupSpectrum& s : spectra) {
    if (s.binned.size() != static_cast<size_t>(rl.grid.bins))
      throw Error("internal error: a spectrum binned on another grid");
    for (const size_t g : relightSourcesOf(image, s.group)) {
      if (given[g]) throw Error("expected each light group once, found '" + s.group + "' twice");
      given[g] = true;
      use[g] = &s.binned;
    }
    relit += (relit.empty() ? "" : ";") + s.group + "=" + s.source;
  }

  SpectralImage out;
  out.width = image.width;
  out.height = image.height;
  out.originX = image.originX;
  out.originY = image.originY;
  out.fullWidth = image.fullWidth;
  out.fullHeight = image.fullHeight;
  out.bands = image.bands;
  out.sampleCount = image.sampleCount;
  out.objectId = image.objectId;
  out.materialId = image.materialId;
  out.depth = image.depth;
  out.attributes = image.attributes;
  out.sourceFiles = image.sourceFiles;
  out.attributes["nxrender.relit"] = relit.empty() ? "(the rendered spectra)" : relit;
  // What the image estimates changed: a relit image is not a part of the render it came from.
  uint64_t digest = fnv1a64("relit");
  for (const auto* s : use)
    for (double v : *s) digest = fnv1a64({reinterpret_cast<const char*>(&v), sizeof v}, digest);
  char key[32];
  std::snprintf(key, sizeof key, "%016llx", static_cast<unsigned long long>(digest));
  out.attributes["nxrender.renderKey"] =
      image.attributes.count("nxrender.renderKey")
          ? image.attributes.at("nxrender.renderKey") + "|relit:" + key
          : std::string("relit:") + key;

  const int nb = image.bands.count();
  const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  out.radiance.assign(pixels * nb, 0.0f);
  out.bandVariance.assign(pixels * nb, 0.0f);
  out.xyz.assign(pixels * 3, 0.0f);
  out.rgb.assign(pixels * 3, 0.0f);
  out.yVariance.assign(pixels, 0.0f);
  const size_t entries = rl.size();
  // Colour from the relit bands (as for a file without its own XYZ): bands in wavelength order.
  std::vector<int> order(static_cast<size_t>(nb));
  for (int b = 0; b < nb; ++b) order[static_cast<size_t>(b)] = b;
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return image.bands.centroid(a) < image.bands.centroid(b); });
  std::vector<double> nm;
  for (int b : order) nm.push_back(image.bands.centroid(b));
  const BandColour colour(nm);
  // The components, when the transport tells them apart: the fluoresced light is the entries
  // only re-radiated light reaches and the fluoresced parts; the reflected the rest.
  if (rl.split)
    for (const char* name : {"reflected", "fluoresced"})
      out.layers.push_back(
          {name, std::vector<float>(pixels * nb, 0.0f), std::vector<float>(pixels * nb, 0.0f)});
  tbb::parallel_for(size_t{0}, pixels, [&](size_t i) {
    // [0] all light, [1] reflected, [2] fluoresced: sums over the entries with the entry's
    // coefficient in each (a fluoresced part moves its light from reflected to fluoresced).
    std::vector<double> mean(3 * static_cast<size_t>(nb), 0.0), half(mean.size(), 0.0);
    for (size_t g = 0; g < rl.sources.size(); ++g) {
      const std::vector<double>& s = *use[g];
      for (size_t e = 0; e < entries; ++e) {
        const size_t k = (g * entries + e) * pixels + i;
        const RelightEntry& en = rl.entries[e];
        const double w = s[static_cast<size_t>(en.bin)];
        const double m = w * rl.values[k], h = w * rl.halfDifferences[k];
        const size_t row = static_cast<size_t>(en.row);
        if (en.fluoresced) {
          mean[nb + row] -= m, half[nb + row] -= h;
          mean[2 * nb + row] += m, half[2 * nb + row] += h;
          continue;
        }
        mean[row] += m, half[row] += h;
        const size_t part = (en.diagonal ? 1 : 2) * static_cast<size_t>(nb) + row;
        mean[part] += m, half[part] += h;
      }
    }
    for (size_t l = 0; l < out.layers.size(); ++l)
      for (int b = 0; b < nb; ++b) {
        const size_t u = (l + 1) * static_cast<size_t>(nb) + static_cast<size_t>(b);
        out.layers[l].values[i * nb + b] = static_cast<float>(mean[u]);
        out.layers[l].variances[i * nb + b] = static_cast<float>(half[u] * half[u]);
      }
    std::vector<float> sortedMean(static_cast<size_t>(nb)), sortedHalf(static_cast<size_t>(nb));
    for (int b = 0; b < nb; ++b) {
      const size_t u = static_cast<size_t>(b);
      out.radiance[i * nb + b] = static_cast<float>(mean[u]);
      out.bandVariance[i * nb + b] = static_cast<float>(half[u] * half[u]);
      sortedMean[u] = static_cast<float>(mean[static_cast<size_t>(order[u])]);
      sortedHalf[u] = static_cast<float>(half[static_cast<size_t>(order[u])]);
    }
    // Y is linear in the bands: its half-difference is the same sum of theirs.
    setPixelColour(out, i, colour.xyz(sortedMean.data()));
    const double halfY = colour.xyz(sortedHalf.data()).y;
    out.yVariance[i] = static_cast<float>(halfY * halfY);
  });
  // Every value a float holds (the new spectra times the transport, and their squares in the
  // variances): what overflowed was found only at the write, or returned as inf to Python.
  std::vector<const std::vector<float>*> checked{&out.radiance, &out.bandVariance, &out.xyz,
                                                 &out.yVariance};
  for (const ImageLayer& l : out.layers)
    checked.push_back(&l.values), checked.push_back(&l.variances);
  for (const auto* v : checked)
    for (size_t k = 0; k < v->size(); ++k)
      if (!std::isfinite((*v)[k])) {
        const size_t per = v->size() / pixels, i = k / per;
        throw Error(
            "expected a relit image whose values and variances a float holds (3.4e38), "
            "found an overflow at pixel " +
            std::to_string(i % static_cast<size_t>(image.width)) + "," +
            std::to_string(i / static_cast<size_t>(image.width)) +
            (per == static_cast<size_t>(nb)
                 ? " in band " + numberText(image.bands.centroid(static_cast<int>(k % per))) + " nm"
                 : std::string()) +
            (relit.empty() ? std::string(" (its rendered spectra)") : " relit with " + relit));
      }
  return out;
}

} // namespace nx
