// One render as the command line and the Python module run it.

#include "apps/render_job.h"

#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "core/hash.h"
#include "core/text_table.h"
#include "io/camera_attributes.h"
#include "spectra/colour.h"

namespace nx {
namespace {

std::string hex(uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

// One of `names`, else nx::Error "option: expected a, b or c, found 'x'".
void requireOneOf(const std::string& value, const std::vector<std::string>& names,
                  const char* option) {
  std::string list;
  size_t i = 0;
  for (const std::string& n : names) {
    if (value == n) return;
    list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + n;
    ++i;
  }
  throw Error(std::string(option) + ": expected " + list + ", found '" + value + "'");
}

// --error-of: luminance, bands, or bands:LO-HI.
ErrorMeasure errorMeasureFrom(const std::string& text) {
  ErrorMeasure m;
  if (text == "luminance") return m;
  m.bands = true;
  if (text == "bands") return m;
  const auto dash = text.find('-', 7);
  if (text.rfind("bands:", 0) != 0 || dash == std::string::npos)
    throw Error("--error-of: expected luminance, bands or bands:LO-HI (nm), found '" + text + "'");
  m.loNm = parseNumber(text.substr(6, dash - 6), "--error-of", "a wavelength in nm");
  m.hiNm = parseNumber(text.substr(dash + 1), "--error-of", "a wavelength in nm");
  if (!(m.hiNm >= m.loNm)) throw Error("--error-of: expected LO <= HI, found '" + text + "'");
  return m;
}

} // namespace

const std::vector<StrategyOption>& strategyOptions() {
  static const std::vector<StrategyOption> options{
      {&RenderChoices::sampler,
       "--sampler",
       {"stratified", "sobol", "independent"},
       "stratified (default: Owen-scrambled Sobol, each pixel's wavelengths stratified over its "
       "samples), sobol (the same with each sample's lanes from one coordinate: more noise per "
       "band; the earlier default) or independent (uniform random numbers)"},
      {&RenderChoices::lightSampling,
       "--light-sampling",
       {"mis", "bsdf", "nee"},
       "mis (default), bsdf or nee: how diffuse surfaces find lights"},
      {&RenderChoices::lightSelection,
       "--light-selection",
       {"local", "tree", "power", "uniform"},
       "local (default: by the power each light sends to the shading point), tree (down a light "
       "tree over all lights: the same weights, in time growing with the log of their number), "
       "power (by emitted power) or uniform: how next-event estimation chooses a light"},
      {&RenderChoices::density,
       "--wavelength-density",
       {"sensor", "visible"},
       "sensor (default: half the lanes over the bands, each band the same share, half over the "
       "visible range for XYZ and the preview) or visible (the eye's density alone, as earlier "
       "versions)"}};
  // Each option's default is listed first, as RenderChoices declares it (checked once here, so
  // that --help, the Python defaults and the render key cannot disagree).
  static const bool defaultsListedFirst = [] {
    const RenderChoices defaults;
    for (const StrategyOption& o : options)
      if (defaults.*o.field != o.values.front())
        throw Error(std::string("internal error: ") + o.option + "'s default '" +
                    defaults.*o.field + "' is not the first of its values");
    return true;
  }();
  (void)defaultsListedFirst;
  return options;
}

Sensor sensorFromOption(const std::string& text, const std::string& option) {
  for (const char* prefix : {"gaussian:", "boxes:", "table:"})
    if (text.rfind(prefix, 0) == 0) return Sensor::parse(text, option);
  std::error_code ec;
  if (!std::filesystem::exists(text, ec) && text.find(':') != std::string::npos)
    return Sensor::parse(text, option);
  return Sensor::readCsv(text);
}

// The ground-truth layers in a render key ("aov:normals,albedo|"; "" without them), in the
// order they are stored.
std::string aovKey(std::vector<AovKind> kinds) {
  std::string key;
  for (AovKind k : kAovKinds)
    if (std::find(kinds.begin(), kinds.end(), k) != kinds.end())
      key += (key.empty() ? "aov:" : ",") + std::string(aovName(k));
  return key.empty() ? key : key + "|";
}

namespace {

// The extra layers besides the ground truth: their names, their flags and what they hold.
struct ExtraAov {
  const char* name;
  bool RenderChoices::*flag;
  const char* doc;
};
const ExtraAov kExtraAovs[] = {
    {"white", &RenderChoices::aovWhite,
     "white.S0.<band>: the radiance a white Lambertian surface would reflect at the first hit, "
     "for flat-fielding; one more path per sample"},
    {"ids", &RenderChoices::aovIds, "ObjectId, MaterialId at the pixel centre; 0 = none"},
    {"depth", &RenderChoices::aovDepth, "Depth: camera-space z at the pixel centre; 0 = none"},
    {"components", &RenderChoices::aovComponents,
     "reflected., fluoresced., direct., indirect.S0.<band>nm: the radiance split by path class, "
     "with variances; docs/components.md"},
    {"lightgroups", &RenderChoices::aovLightGroups,
     "light.NAME.S0.<band>nm per light group, group=\"NAME\" on emitters"},
};

// A ground-truth layer's channels as --help shows them.
std::string channelsOf(AovKind k) {
  const std::string name = aovName(k);
  switch (aovLayout(k)) {
  case AovLayout::Vector:
    return ".X, .Y, .Z";
  case AovLayout::Uv:
    return ".U, .V";
  case AovLayout::PerBand:
    return name + ".T.<band>nm";
  case AovLayout::AbsorptionEmission:
    return name + ".absorption.T.<band>nm and " + name + ".emission.S0.<band>nm";
  }
  return "";
}

} // namespace

bool addAov(RenderChoices& choices, const std::string& name) {
  if (const auto kind = aovKindNamed(name)) {
    if (std::find(choices.aovKinds.begin(), choices.aovKinds.end(), *kind) ==
        choices.aovKinds.end())
      choices.aovKinds.push_back(*kind);
    return true;
  }
  for (const ExtraAov& a : kExtraAovs)
    if (name == a.name) {
      choices.*a.flag = true;
      return true;
    }
  return false;
}

std::string aovOptionList(const std::string& quote, const std::string& last) {
  std::vector<std::string> names;
  for (const ExtraAov& a : kExtraAovs) names.push_back(a.name);
  for (AovKind k : kAovKinds) names.push_back(aovName(k));
  std::string out;
  for (size_t i = 0; i < names.size(); ++i)
    out += (i == 0 ? "" : i + 1 == names.size() ? last : ", ") + quote + names[i] + quote;
  return out;
}

std::string aovOptionHelp() {
  std::string out = "Extra channels, a comma list of: ";
  for (const ExtraAov& a : kExtraAovs) out += std::string(a.name) + " (" + a.doc + "), ";
  out += "and ground truth of the first hit, averaged over each pixel's samples like the "
         "radiance (docs/datasets.md): ";
  for (size_t i = 0; i < std::size(kAovKinds); ++i) {
    const AovKind k = kAovKinds[i];
    out += (i == 0 ? "" : ", ") + std::string(aovName(k)) + " (" + channelsOf(k) + ": " +
           aovDoc(k) + ")";
  }
  return out;
}

RenderJob::RenderJob(const RenderScene& scene, std::string scenePath, const RenderChoices& choices)
    : scene_(scene), scenePath_(std::move(scenePath)), choices_(choices) {
  const int width = scene.settings.width, height = scene.settings.height;
  for (const StrategyOption& o : strategyOptions())
    requireOneOf(choices.*o.field, o.values, o.option);
  if (choices.samples < 0 || choices.samples > (1 << 30) || choices.firstSample < 0 ||
      static_cast<long long>(choices.firstSample) + choices.samples > (1LL << 30))
    throw Error("--spp-range: expected 0 <= A < B <= 2^30, found " +
                std::to_string(choices.firstSample) + ":" +
                std::to_string(static_cast<long long>(choices.firstSample) + choices.samples));
  if (choices.crop) {
    const PixelRect& c = *choices.crop;
    if (c.x0 < 0 || c.y0 < 0 || c.x1 > width || c.y1 > height || c.x1 <= c.x0 || c.y1 <= c.y0)
      throw Error("--crop: expected 0 <= X0 < X1 <= " + std::to_string(width) +
                  " and 0 <= Y0 < Y1 <= " + std::to_string(height) + ", found " +
                  std::to_string(c.x0) + "," + std::to_string(c.y0) + "," + std::to_string(c.x1) +
                  "," + std::to_string(c.y1));
  }
  options_.samples = choices.samples;
  options_.firstSample = choices.firstSample;
  options_.crop = choices.crop;
  options_.seed = choices.seed;
  options_.bands = choices.bands;
  options_.lightSampling = choices.lightSampling == "bsdf"  ? LightSampling::BsdfOnly
                           : choices.lightSampling == "nee" ? LightSampling::NeeOnly
                                                            : LightSampling::Mis;
  options_.lightSelection = choices.lightSelection == "power"     ? LightSelection::Power
                            : choices.lightSelection == "uniform" ? LightSelection::Uniform
                            : choices.lightSelection == "tree"    ? LightSelection::Tree
                                                                  : LightSelection::Local;
  options_.sampler =
      choices.sampler == "independent" ? SamplerKind::Independent : SamplerKind::SobolOwen;
  options_.stratifiedLanes = choices.sampler == "stratified";
  options_.wavelengthDensity =
      choices.density == "visible" ? WavelengthDensity::Visible : WavelengthDensity::Sensor;
  options_.whiteReference = choices.aovWhite;
  options_.components = choices.aovComponents;
  options_.lightGroups = choices.aovLightGroups;
  options_.aovs = choices.aovKinds;
  options_.targetRelativeError = choices.targetError;
  options_.errorMeasure = errorMeasureFrom(choices.errorOf);
  options_.timeLimitSeconds = choices.timeLimit;
  if (choices.adaptive) {
    if (!(choices.targetError > 0))
      throw Error("--adaptive: expected a --target-error to aim at, found none");
    if (choices.sampleRange)
      throw Error("--adaptive with --spp-range: an adaptive render splits by crops only (each "
                  "pixel's count depends on the samples before it); see docs/farm.md");
    if (choices.adaptiveMinSamples < 2)
      throw Error("--adaptive-min-spp: expected at least 2 (one sample per replicate), found " +
                  std::to_string(choices.adaptiveMinSamples));
  }
  options_.adaptive = choices.adaptive;
  options_.adaptiveMinSamples = choices.adaptiveMinSamples;
  if (choices.relightable != scene.relight.enabled)
    throw Error("internal error: --relightable needs the scene built relightable");
  options_.relightStepNm = choices.relightStepNm;

  // Relighting targets change what a relightable render draws (not what it estimates).
  std::string targets;
  if (!scene.relight.targetsOfSource.empty()) {
    uint64_t h = fnv1a64("relightFor");
    for (const std::vector<Spectrum>& ofSource : scene.relight.targetsOfSource)
      for (const Spectrum& t : ofSource)
        for (int nm = 300; nm <= 1100; ++nm) {
          const double v = t(nm);
          h = fnv1a64({reinterpret_cast<const char*>(&v), sizeof v}, h);
        }
    targets = "relightFor:" + hex(h) + "|";
  }
  renderKey_ = hex(fnv1a64(
      std::string(NX_VERSION) + "|" + choices.sampler + "|" + choices.lightSampling + "|" +
          choices.lightSelection + "|" + choices.density + "|" +
          (choices.aovWhite ? "white|" : "") + (choices.aovComponents ? "components|" : "") +
          (choices.aovLightGroups ? "lightgroups|" : "") + aovKey(choices.aovKinds) +
          (choices.relightable ? "relight:" + numberText(choices.relightStepNm) + "|" : "") +
          targets + (choices.noFluorescence ? "nofl" : "fl") + "|" + std::to_string(kLanes),
      scene.contentDigest));
  seed_ = choices.seed ? *choices.seed : scene.settings.seed;
  bands_ = choices.bands ? *choices.bands : scene.settings.bands;
  firstSample_ = choices.firstSample;
  samples_ = choices.samples > 0 ? choices.samples : scene.settings.samples;
  if (choices.adaptive && samples_ < 2)
    throw Error("--adaptive: expected at least 2 samples per pixel (one per replicate), found " +
                std::to_string(samples_));
}

PixelRect RenderJob::rect() const {
  return choices_.crop ? *choices_.crop
                       : PixelRect{0, 0, scene_.settings.width, scene_.settings.height};
}

SpectralImage RenderJob::image(const Film& film, double seconds) const {
  SpectralImage image = toSpectralImage(film);
  const Xyz white = spectrumToXyz(scene_.previewWhite);
  image.attributes["nxrender.version"] = NX_VERSION;
  image.attributes["nxrender.scene"] = scenePath_;
  image.attributes["nxrender.renderKey"] = renderKey_;
  image.attributes["nxrender.mode"] = renderModeName(scene_.settings.mode);
  image.attributes["nxrender.sampleRange"] =
      std::to_string(firstSample_) + ":" + std::to_string(firstSample_ + samples_);
  image.attributes["nxrender.seed"] = std::to_string(seed_);
  image.attributes["nxrender.bands"] = film.bands().toString();
  image.attributes["nxrender.sampler"] = choices_.sampler;
  image.attributes["nxrender.lightSampling"] = choices_.lightSampling;
  image.attributes["nxrender.lightSelection"] = choices_.lightSelection;
  image.attributes["nxrender.fluorescence"] = scene_.hasFluorescence ? "on" : "off";
  image.attributes["nxrender.previewWhite"] = std::to_string(white.x / white.y) + "," +
                                              std::to_string(1.0) + "," +
                                              std::to_string(white.z / white.y);
  image.attributes["nxrender.renderSeconds"] = std::to_string(seconds);
  image.attributes["nxrender.estimatedRelativeError"] = std::to_string(film.relativeRmsError());
  // Adaptive images hold different counts in different pixels (SampleCount), all within the
  // sample range; the merge accepts such parts of the same target as crops.
  if (choices_.adaptive)
    image.attributes["nxrender.adaptive"] =
        "target " + numberText(choices_.targetError) + " of " + choices_.errorOf;
  for (const auto& [key, value] : cameraAttributes(scene_.camera)) image.attributes[key] = value;
  if (choices_.aovIds || choices_.aovDepth) {
    addGeometryAovs(scene_, image);
    if (!choices_.aovIds) image.objectId.clear(), image.materialId.clear();
    if (choices_.aovIds) { // the ids' names, one "id<TAB>label" line each
      std::string labels;
      for (size_t i = 0; i < scene_.objectLabels.size(); ++i)
        labels += std::to_string(i + 1) + "\t" + scene_.objectLabels[i] + "\n";
      image.attributes["nxrender.objectLabels"] = labels;
    }
    if (!choices_.aovDepth) image.depth.clear();
  }
  return image;
}

} // namespace nx
