#include "io/relight_channels.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <tuple>

#include "core/error.h"
#include "core/number_text.h"
#include "core/text_table.h"
#include "spectra/spectrum.h"

namespace nx {
namespace {

// "452,500000nm": a wavelength as the spectral channels write it.
std::string wavelengthText(double nm) {
  std::string s = fixedText(nm, 6);
  std::replace(s.begin(), s.end(), '.', ',');
  return s + "nm";
}

double parseWavelength(const std::string& text, const std::string& path,
                       const std::string& channel) {
  const std::string where = path + ": channel " + channel;
  if (text.size() < 3 || text.substr(text.size() - 2) != "nm")
    throw Error(where + ": expected a wavelength in nm, found '" + text + "'");
  std::string s = text.substr(0, text.size() - 2);
  std::replace(s.begin(), s.end(), ',', '.');
  return parseNumber(s, where, "a wavelength in nm");
}

std::vector<std::string> splitCommas(const std::string& s) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= s.size()) {
    const size_t comma = s.find(',', start);
    out.push_back(s.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

// The diagonal flags of rl's entries from kRelightDiagonalAttribute (removed), which makes the
// transport split; without it a fluoresced part is refused (it cannot be told apart).
void readDiagonal(std::map<std::string, std::string>& attributes, int bands,
                  const std::string& path, RelightLayers& rl) {
  const auto it = attributes.find(kRelightDiagonalAttribute);
  const std::string where = path + ": " + kRelightDiagonalAttribute;
  if (it == attributes.end()) {
    for (const RelightEntry& e : rl.entries)
      if (e.fluoresced)
        throw Error(path + ": expected the attribute " + kRelightDiagonalAttribute +
                    " beside fluoresced relight channels, found none");
    return;
  }
  const std::vector<std::string> ranges = splitCommas(it->second);
  if (ranges.size() != static_cast<size_t>(bands))
    throw Error(where + ": expected one range per band (" + std::to_string(bands) + "), found " +
                std::to_string(ranges.size()));
  std::vector<std::pair<double, double>> nm;
  for (const std::string& r : ranges) {
    const size_t colon = r.find(':');
    if (r == "none") {
      nm.push_back({0, 0});
      continue;
    }
    if (colon == std::string::npos)
      throw Error(where + ": expected LO:HI in nm or none, found '" + r + "'");
    nm.push_back({parseNumber(r.substr(0, colon), where, "a wavelength in nm"),
                  parseNumber(r.substr(colon + 1), where, "a wavelength in nm")});
  }
  for (size_t k = 0; k < rl.entries.size(); ++k) {
    RelightEntry& e = rl.entries[k];
    if (e.fluoresced && !(k > 0 && rl.entries[k - 1].row == e.row &&
                          rl.entries[k - 1].bin == e.bin && !rl.entries[k - 1].fluoresced))
      throw Error(path +
                  ": expected a fluoresced relight channel beside the total of its pair, "
                  "found one alone at " +
                  numberText(rl.grid.centre(e.bin)) + " nm");
    const auto& [lo, hi] = nm[static_cast<size_t>(e.row)];
    e.diagonal = rl.grid.lo(e.bin) >= lo - 1e-6 && rl.grid.lo(e.bin + 1) <= hi + 1e-6;
    if (e.fluoresced && !e.diagonal)
      throw Error(where + ": expected the fluoresced part's bin " +
                  numberText(rl.grid.centre(e.bin)) + " nm inside the range of its band (" +
                  ranges[static_cast<size_t>(e.row)] + "), found it outside");
  }
  rl.split = true;
  attributes.erase(it);
}

} // namespace

std::string relightChannelText(const std::string& source, const std::string& excitation,
                               const std::string& band) {
  return "relight." + source + ".T." + excitation + "." + band;
}

std::string relightChannelName(const RelightLayers& rl, size_t g, size_t e,
                               const std::vector<std::string>& bandText) {
  const RelightEntry& en = rl.entries[e];
  return relightChannelText(
      rl.sources[g] + (en.fluoresced ? std::string(".") + kRelightFluorescedLayer : std::string()),
      wavelengthText(rl.grid.centre(en.bin)), bandText[static_cast<size_t>(en.row)]);
}

void checkRelightValues(const RelightLayers& rl, const std::vector<std::string>& channels,
                        int width, int height, const std::string& path) {
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
  for (size_t k = 0; k < channels.size(); ++k)
    for (const bool half : {false, true}) {
      const float* v = (half ? rl.halfDifferences : rl.values).data() + k * pixels;
      for (size_t i = 0; i < pixels; ++i) {
        const double x = v[i];
        if (half ? std::abs(x) <= kMaxTransportValue : x >= 0 && x <= kMaxTransportValue) continue;
        throw Error(
            path + ": channel " + (half ? kHalfDifferencePrefix : "") + channels[k] +
            ": expected " + (half ? "half-differences within +-" : "transport values within [0, ") +
            numberText(kMaxTransportValue) + (half ? "" : "]") +
            " (what an emission at the 1e12 limit relights into a float), found " + numberText(x) +
            " at pixel " + std::to_string(i % width) + "," + std::to_string(i / width));
      }
    }
}

std::map<std::string, std::string> relightAttributes(const RelightLayers& rl) {
  std::map<std::string, std::string> out;
  std::string groups;
  for (const std::string& g : rl.sources) groups += (groups.empty() ? "" : ",") + g;
  out[kRelightSourcesAttribute] = groups;
  out[kRelightGridAttribute] = generalText(rl.grid.firstNm, 9) + ":" +
                               generalText(rl.grid.lo(rl.grid.bins), 9) + ":" +
                               generalText(rl.grid.stepNm, 9);
  if (rl.split) { // per row, the excitation range of its diagonal entries
    int rows = 0;
    for (const RelightEntry& e : rl.entries) rows = std::max(rows, e.row + 1);
    std::vector<std::pair<int, int>> range(static_cast<size_t>(rows), {-1, -1});
    for (const RelightEntry& e : rl.entries)
      if (e.diagonal) {
        auto& r = range[static_cast<size_t>(e.row)];
        r = {r.first < 0 ? e.bin : std::min(r.first, e.bin), std::max(r.second, e.bin)};
      }
    std::string text;
    for (const auto& [first, last] : range) {
      text += (text.empty() ? "" : ",") + (first < 0 ? std::string("none")
                                                     : generalText(rl.grid.lo(first), 9) + ":" +
                                                           generalText(rl.grid.lo(last + 1), 9));
    }
    out[kRelightDiagonalAttribute] = text;
  }
  const auto listed = [](const std::vector<double>& bins) {
    std::string values;
    for (double v : bins) {
      if (!values.empty()) values += ',';
      values += generalText(v, 9);
    }
    return values;
  };
  for (size_t g = 0; g < rl.sources.size(); ++g) {
    out[kRelightSpectrumAttribute + rl.sources[g]] = listed(rl.spectra[g]);
    if (!rl.guides.empty())
      for (size_t k = 0; k < rl.guides[g].size(); ++k)
        out[kRelightGuideAttribute + rl.sources[g] + "." + std::to_string(k + 1)] =
            listed(rl.guides[g][k]);
  }
  return out;
}

std::vector<std::string> parseRelightChannels(std::map<std::string, std::string>& attributes,
                                              const std::vector<std::string>& channels,
                                              const std::vector<std::string>& bandText,
                                              const std::string& path, RelightLayers& rl) {
  const auto groupsIt = attributes.find(kRelightSourcesAttribute);
  if (groupsIt == attributes.end()) return {};
  rl.sources = splitCommas(groupsIt->second);
  attributes.erase(groupsIt);
  const auto gridIt = attributes.find(kRelightGridAttribute);
  if (gridIt == attributes.end())
    throw Error(path + ": expected the attribute " + std::string(kRelightGridAttribute) +
                " beside " + kRelightSourcesAttribute + ", found none");
  double first = 0, end = 0, step = 0;
  // FIRST:END:STEP, three numbers and nothing else (read in the C locale).
  const auto threeNumbers = [&](const char* p) {
    const char* q = nullptr;
    double* out[3] = {&first, &end, &step};
    for (int k = 0; k < 3; ++k) {
      *out[k] = strtodC(p, &q);
      if (q == p || *q != (k < 2 ? ':' : '\0')) return false;
      p = q + (k < 2 ? 1 : 0);
    }
    return true;
  };
  if (!threeNumbers(gridIt->second.c_str()))
    throw Error(path + ": expected " + kRelightGridAttribute + " as FIRST:END:STEP, found '" +
                gridIt->second + "'");
  attributes.erase(gridIt);
  checkRelightStep(step, path + ": " + kRelightGridAttribute);
  rl.grid = RelightGrid::withStep(step);
  if (first != rl.grid.firstNm || std::abs(end - rl.grid.lo(rl.grid.bins)) > 1e-6)
    throw Error(path + ": expected " + kRelightGridAttribute + " from " +
                std::to_string(static_cast<int>(rl.grid.firstNm)) + " nm, found '" +
                std::to_string(first) + "'");
  // A source's spectrum attribute (an emission's bin averages, checked as a scene's would be),
  // removed; empty when it is optional and absent.
  const auto binnedAttribute = [&](const std::string& name, const char* what, bool required) {
    const auto it = attributes.find(name);
    std::vector<double> values;
    if (it == attributes.end()) {
      if (required)
        throw Error(path + ": expected the attribute " + name + " (" + what + "), found none");
      return values;
    }
    for (const std::string& v : splitCommas(it->second)) {
      values.push_back(parseNumber(v, path + ": " + it->first, "a number"));
      if (!(values.back() >= 0 && values.back() <= kMaxEmission))
        throw Error(path + ": " + it->first + ": expected bin averages of an emission within [0, " +
                    numberText(kMaxEmission) + "], found " + numberText(values.back()));
    }
    if (values.size() != static_cast<size_t>(rl.grid.bins))
      throw Error(path + ": expected " + std::to_string(rl.grid.bins) + " values in " + it->first +
                  " (one per bin), found " + std::to_string(values.size()));
    attributes.erase(it);
    return values;
  };
  for (const std::string& g : rl.sources)
    rl.spectra.push_back(
        binnedAttribute(kRelightSpectrumAttribute + g, "the source's spectrum", true));
  // The excitation guides of a render told its targets: at least one for every source, or none.
  for (const std::string& g : rl.sources) {
    std::vector<std::vector<double>> guides;
    for (int k = 1;; ++k) {
      std::vector<double> guide =
          binnedAttribute(kRelightGuideAttribute + g + "." + std::to_string(k),
                          "the source's excitation guide", k == 1 && !rl.guides.empty());
      if (guide.empty()) break;
      guides.push_back(std::move(guide));
    }
    if (guides.empty()) break;
    rl.guides.push_back(std::move(guides));
  }
  // The entries of each source from its channel names; every source has the same ones.
  const int bands = static_cast<int>(bandText.size());
  std::vector<std::set<std::tuple<int, int, int>>> ofGroup(rl.sources.size());
  const std::string fluorescedLayer = std::string(".") + kRelightFluorescedLayer;
  for (const std::string& c : channels) {
    if (c.rfind("relight.", 0) != 0) continue;
    size_t g = 0;
    int part = 0;
    // (a source's name is a prefix of its group's further sources': the rest must start "T.",
    // or "fluoresced.T." for a fluoresced part)
    for (; g < rl.sources.size(); ++g) {
      if (c.rfind("relight." + rl.sources[g] + ".T.", 0) == 0) break;
      if (c.rfind("relight." + rl.sources[g] + fluorescedLayer + ".T.", 0) == 0) {
        part = 1;
        break;
      }
    }
    if (g == rl.sources.size())
      throw Error(path + ": expected relight channels of the sources " + kRelightSourcesAttribute +
                  " lists, found " + c);
    const std::string rest =
        c.substr(("relight." + rl.sources[g] + (part ? fluorescedLayer : "") + ".").size());
    if (rest.rfind("T.", 0) != 0 || rest.find('.', 2) == std::string::npos)
      throw Error(path + ": expected relight." + rl.sources[g] +
                  ".T.<excitation>nm.<band>nm, found " + c);
    const size_t dot = rest.find('.', 2);
    const std::string excitation = rest.substr(2, dot - 2), band = rest.substr(dot + 1);
    int row = -1;
    for (int b = 0; b < bands; ++b)
      if (bandText[static_cast<size_t>(b)] == band) row = b;
    if (row < 0)
      throw Error(path + ": expected a band of the image in the channel " + c + ", found " + band);
    const double nm = parseWavelength(excitation, path, c);
    const int bin = rl.grid.binOf(static_cast<float>(nm));
    if (bin < 0 || std::abs(rl.grid.centre(bin) - nm) > 1e-3)
      throw Error(path + ": expected an excitation bin centre of the grid in the channel " + c +
                  ", found " + excitation);
    ofGroup[g].insert({row, bin, part});
  }
  for (size_t g = 1; g < ofGroup.size(); ++g)
    if (ofGroup[g] != ofGroup[0])
      throw Error(path + ": expected the same transport channels for every light group, found " +
                  std::to_string(ofGroup[0].size()) + " for " + rl.sources[0] + " and " +
                  std::to_string(ofGroup[g].size()) + " for " + rl.sources[g]);
  for (const auto& [row, bin, part] : ofGroup[0]) rl.entries.push_back({row, bin, part, 0});
  readDiagonal(attributes, bands, path, rl);
  std::vector<std::string> out;
  for (size_t g = 0; g < rl.sources.size(); ++g)
    for (size_t e = 0; e < rl.entries.size(); ++e) {
      out.push_back(relightChannelName(rl, g, e, bandText));
      if (std::find(channels.begin(), channels.end(), kHalfDifferencePrefix + out.back()) ==
          channels.end())
        throw Error(path + ": expected a channel " + kHalfDifferencePrefix + out.back() +
                    ", found none");
    }
  return out;
}

} // namespace nx
