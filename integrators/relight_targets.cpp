#include "integrators/relight_targets.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/text_table.h"
#include "spectra/illuminants.h"
#include "spectra/reradiation_matrix.h"
#include "spectra/spectrum_bounds.h"

namespace nx {
namespace {

// Bands relit to less than this share of the brightest band's light are left out of the noise
// estimate.
constexpr double kCountedShare = 0.05;

} // namespace

TextSpectrum spectrumFromText(const std::string& text) {
  std::error_code ec;
  if (std::filesystem::exists(text, ec)) {
    TabulatedSpectrum t = readSpectrumCsv(text);
    for (size_t i = 0; i < t.value.size(); ++i)
      if (!(t.value[i] >= 0 && std::isfinite(t.value[i])))
        throw Error(text + ": expected an emission spectrum of values >= 0, found " +
                    numberText(t.value[i]) + " at " + numberText(t.nm[i]) + " nm");
    const double lo = t.nm.front(), hi = t.nm.back();
    t.buildIndex();
    return {Spectrum(std::move(t)), lo, hi};
  }
  const std::optional<Spectrum> named = namedEmission(text);
  if (!named)
    throw Error("expected a CSV file (nm,value) or a built-in emission name (A, D65, F1-F12, "
                "blackbody:K, ...), found '" +
                text + "' (no such file)");
  // Where the built-in is not 0: a table (D illuminants, F1-F12) is 0 beyond its data.
  double lo = 1e9, hi = -1e9;
  for (int nm = 300; nm <= 1100; ++nm)
    if ((*named)(nm) > 0) lo = std::min(lo, double(nm)), hi = std::max(hi, double(nm));
  return {*named, lo, hi};
}

void checkRelightTarget(const RelightTargetDesc& target, const std::string& where) {
  if (target.group.find_first_of(".,=") != std::string::npos)
    throw Error(where + ": expected a light group's name (no '.', ',' or '='), found '" +
                target.group + "'");
  if (const std::string problem = emissionProblem(target.spectrum); !problem.empty())
    throw Error(where + ": " + problem);
  const SpectrumExtremes e = spectrumExtremes(target.spectrum, 300, 1100);
  if (!(e.max > 0))
    throw Error(where + ": expected a spectrum with light somewhere in 300-1100 nm, found 0 "
                        "everywhere (a target to sample for must emit)");
}

RelightTargetDesc relightTargetFromText(const std::string& text, const std::string& option) {
  RelightTargetDesc t;
  std::string spec = text;
  // GROUP=SPEC, unless the whole text names a file (a file name may hold '=').
  std::error_code ec;
  if (const size_t eq = text.find('=');
      eq != std::string::npos && !std::filesystem::exists(text, ec)) {
    t.group = text.substr(0, eq);
    spec = text.substr(eq + 1);
    if (t.group.empty())
      throw Error(option + ": expected GROUP=SPECTRUM or SPECTRUM, found '" + text + "'");
  }
  try {
    t.spectrum = spectrumFromText(spec).spectrum;
  } catch (const Error& e) {
    throw Error(option + " " + text + ": " + e.what());
  }
  t.source = spec;
  t.option = option;
  t.where = option + " " + text;
  checkRelightTarget(t, t.where);
  return t;
}

namespace {

// The wavelengths a target's integral and the mixture are taken at: every 0.1 nm over the
// traced range (a laser line's width), and every knot of a tabulated target there, so a line
// narrower than the grid, or lying between its points, is integrated exactly (its table is
// linear between its knots); integrated on the 0.1 nm grid alone, such a line had integral 0.
std::vector<double> targetGrid(const std::vector<const Spectrum*>& spectra) {
  constexpr int kSteps = 8000;
  constexpr double kLoNm = 300, kHiNm = 1100, kStepNm = (kHiNm - kLoNm) / kSteps;
  std::vector<double> nm;
  for (int k = 0; k <= kSteps; ++k) nm.push_back(kLoNm + kStepNm * k);
  for (const Spectrum* s : spectra)
    if (const auto* t = std::get_if<TabulatedSpectrum>(&s->kind()))
      for (double x : t->nm)
        if (x > kLoNm && x < kHiNm) nm.push_back(x);
  std::sort(nm.begin(), nm.end());
  nm.erase(std::unique(nm.begin(), nm.end()), nm.end());
  return nm;
}

// The targets' mixture, tabulated on targetGrid: the mean of their shapes, each normalised to
// unit integral over the range, so that each draws an equal share of the guided excitation
// however bright it is, scaled to their mean integral (the lights' power for the choice among
// them). Only the render's set-up reads it (guides and light powers). A target whose integral
// is not positive is refused (checkRelightTarget refuses one that is 0 everywhere).
Spectrum targetMixture(const std::vector<const Spectrum*>& spectra, const std::string& option) {
  const std::vector<double> nm = targetGrid(spectra);
  std::vector<double> integral;
  for (const Spectrum* s : spectra) {
    double sum = 0;
    for (size_t k = 0; k + 1 < nm.size(); ++k)
      sum += 0.5 * ((*s)(nm[k]) + (*s)(nm[k + 1])) * (nm[k + 1] - nm[k]);
    if (!(sum > 0))
      throw Error(option +
                  ": expected a target spectrum with light in 300-1100 nm, found "
                  "its integral there " +
                  std::to_string(sum));
    integral.push_back(sum);
  }
  double meanIntegral = 0;
  for (double i : integral) meanIntegral += i / static_cast<double>(spectra.size());
  TabulatedSpectrum t;
  for (double x : nm) {
    double sum = 0;
    for (size_t i = 0; i < spectra.size(); ++i) sum += (*spectra[i])(x) / integral[i];
    t.nm.push_back(x);
    t.value.push_back(sum / static_cast<double>(spectra.size()) * meanIntegral);
  }
  t.buildIndex();
  return Spectrum(std::move(t));
}

} // namespace

void setRelightTargets(RenderScene& scene, const std::vector<RelightTargetDesc>& targets) {
  RelightSpectra& r = scene.relight;
  r.samplingOfSource.clear();
  r.targetsOfSource.clear();
  if (targets.empty()) return;
  const LightGroups& groups = scene.lightGroups;
  for (const RelightTargetDesc& t : targets) {
    if (t.group.empty()) continue;
    const bool known = std::any_of(r.groupOfSource.begin(), r.groupOfSource.end(),
                                   [&](uint16_t g) { return groups.names[g] == t.group; });
    if (!known) {
      std::string list;
      for (size_t s = 0; s < r.groupOfSource.size(); ++s) {
        const std::string& n = groups.names[r.groupOfSource[s]];
        if (list.find(n) == std::string::npos) list += (list.empty() ? "" : ", ") + n;
      }
      throw Error(t.where + ": expected a light group of the scene (" + list + "), found '" +
                  t.group + "'");
    }
  }
  for (size_t s = 0; s < r.ofSource.size(); ++s) {
    std::vector<const Spectrum*> mine;
    for (const RelightTargetDesc& t : targets)
      if (t.group.empty() || t.group == groups.names[r.groupOfSource[s]])
        mine.push_back(&t.spectrum);
    if (mine.size() > static_cast<size_t>(kMaxExcitationGuides))
      throw Error(targets.front().option + ": expected at most " +
                  std::to_string(kMaxExcitationGuides) +
                  " targets for a light group (one excitation draw each), found " +
                  std::to_string(mine.size()) + " for '" + groups.names[r.groupOfSource[s]] +
                  "'; relight the others from a second render");
    r.samplingOfSource.push_back(mine.empty() ? r.ofSource[s]
                                              : targetMixture(mine, targets.front().option));
    r.targetsOfSource.emplace_back();
    for (const Spectrum* t : mine) r.targetsOfSource.back().push_back(*t);
    if (mine.empty()) r.targetsOfSource.back().push_back(r.ofSource[s]);
  }
}

RelitNoise relitNoiseFactor(const SpectralImage& image, const std::vector<size_t>& sources,
                            const std::vector<double>& binned) {
  const RelightLayers& rl = image.relight;
  RelitNoise out;
  if (sources.empty()) return out;
  const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  const size_t rows = static_cast<size_t>(image.bands.count());
  // The guides a targeted render drew excitation towards (the first source's: a group's sources
  // share its targets), each its own technique beside the matrices' choice.
  static const std::vector<std::vector<double>> kNone;
  const std::vector<std::vector<double>>& guides =
      rl.guides.empty() ? kNone : rl.guides[sources.front()];
  const size_t ng = std::min(guides.size(), static_cast<size_t>(kMaxExcitationGuides));
  // Per pixel and row, sums over the total entries (the choices a draw makes: the elastic one
  // and each excitation bin) of T, T S, T S^2, and per guide T g and T S^2 / g; and the
  // fluoresced light relit.
  struct Sums {
    double t = 0, ts = 0, tss = 0, fluoresced = 0;
    double tg[kMaxExcitationGuides] = {}, tssOverG[kMaxExcitationGuides] = {};
  };
  std::vector<Sums> sums(rows * pixels);
  for (const size_t g : sources)
    for (size_t e = 0; e < rl.size(); ++e) {
      const RelightEntry& en = rl.entries[e];
      const float* v = rl.values.data() + (g * rl.size() + e) * pixels;
      Sums* row = sums.data() + static_cast<size_t>(en.row) * pixels;
      const size_t bin = static_cast<size_t>(en.bin);
      const double sj = binned[bin];
      const bool fluoresced = en.fluoresced || (rl.split && !en.diagonal);
      for (size_t i = 0; i < pixels; ++i) {
        if (v[i] == 0) continue;
        if (fluoresced) row[i].fluoresced += v[i] * sj;
        if (en.fluoresced) continue; // a part of the total beside it
        const double t = v[i];
        row[i].t += t, row[i].ts += t * sj, row[i].tss += t * sj * sj;
        for (size_t k = 0; k < ng; ++k) {
          const double gj = guides[k][bin];
          row[i].tg[k] += t * gj;
          row[i].tssOverG[k] += gj > 0 ? t * sj * sj / gj : (sj > 0 ? INFINITY : 0);
        }
      }
    }
  // Per row, the pixels' second moments F against drawing in proportion to T S (the draws
  // follow T, or T g for a guide's; with several techniques combined by MIS, about the best
  // one's), pooled with the weight of each pixel's relit value squared (its share of the band's
  // variance), over the pixels where fluoresced light is most of the band when the transport is
  // split (where the draws matter).
  std::vector<double> weight(rows, 0.0), pooled(rows, 0.0);
  for (size_t r = 0; r < rows; ++r)
    for (size_t i = 0; i < pixels; ++i) {
      const Sums& p = sums[r * pixels + i];
      if (!(p.t > 0 && p.ts > 0) || (rl.split && !(p.fluoresced > 0.5 * p.ts))) continue;
      double second = p.tss * p.t / (p.ts * p.ts);
      for (size_t k = 0; k < ng; ++k)
        if (p.tg[k] > 0) second = std::min(second, p.tssOverG[k] * p.tg[k] / (p.ts * p.ts));
      weight[r] += p.ts * p.ts;
      pooled[r] += p.ts * p.ts * second;
    }
  // Only bands holding a fair share of that light count (a lamp's faint tail is noisy in
  // relative terms, and no one looks at it).
  const double heaviest = *std::max_element(weight.begin(), weight.end());
  for (size_t r = 0; r < rows; ++r) {
    if (!(weight[r] > 0) || weight[r] < kCountedShare * kCountedShare * heaviest) continue;
    const double factor = std::sqrt(std::max(1.0, pooled[r] / weight[r]));
    if (!(factor > out.factor)) continue;
    out.factor = factor;
    out.band = static_cast<int>(r);
    double fl = 0, all = 0;
    for (size_t i = 0; i < pixels; ++i)
      fl += sums[r * pixels + i].fluoresced, all += sums[r * pixels + i].ts;
    out.fluorescedShare = all > 0 ? fl / all : 0;
  }
  return out;
}

} // namespace nx
