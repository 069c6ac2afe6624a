#include "integrators/scene_params/scene_fields.h"

#include <cmath>

#include "core/file_text.h"
#include "core/params/concentration_map.h"
#include "core/params/scene_limits.h"
#include "core/params/scene_parameters.h"
#include "integrators/scene_params/parameter_path.h"
#include "io/camera_checks.h"

namespace nx {
namespace {

[[noreturn]] void noField(const std::string& name) {
  throw Error("no scene parameter named '" + name + "' (Scene.parameters() lists them)");
}

// Where a field is: the item holding it and the field's leaf name.
struct FieldPlace {
  enum class Kind { Setting, Spectrum, Camera, Object, Fluorescence, DyePeak } kind;
  std::string leaf;
  NamedSpectrumDesc* spectrum = nullptr;
  ObjectDesc* object = nullptr;
  FluorescenceDesc* fluorescence = nullptr;
  std::string refusal = {}; ///< why it cannot be set here (a material used by reference), or ""
};

FluorescenceDesc* fluorescenceOf(ParameterSet& p, const std::string& name) {
  FluorescenceDesc* f = p.getMutable<FluorescenceDesc>("fluorescence");
  if (!f) throw Error(name + ": no fluorescence here");
  return f;
}

FieldPlace placeOf(SceneDesc& d, const std::string& name) {
  const std::vector<ParameterStep> s = parameterSteps(name);
  const std::string& top = s[0].attribute;
  if (s.size() == 1) return {FieldPlace::Kind::Setting, top};
  if (top == "camera" && s.size() == 2 && s[0].index.index() == 0)
    return {FieldPlace::Kind::Camera, s[1].attribute};
  if (top == "spectra" && s.size() == 2 && s[1].attribute == "value")
    if (const auto* key = std::get_if<std::string>(&s[0].index))
      for (NamedSpectrumDesc& n : d.spectra)
        if (n.name == *key) return {FieldPlace::Kind::Spectrum, "value", &n};
  if (top == "materials" && s.size() == 3 && s[1].attribute == "fluorescence")
    if (const auto* key = std::get_if<std::string>(&s[0].index))
      for (NamedMaterialDesc& m : d.materials)
        if (m.id == *key)
          return {FieldPlace::Kind::Fluorescence, s[2].attribute, nullptr, nullptr,
                  fluorescenceOf(m.material.params, name)};
  const size_t* i = std::get_if<size_t>(&s[0].index);
  if (top != "objects" || !i || *i >= d.objects.size()) noField(name);
  ObjectDesc& o = d.objects[*i];
  const std::string label = "objects[" + std::to_string(*i) + "]";
  if (s.size() == 2) return {FieldPlace::Kind::Object, s[1].attribute, nullptr, &o};
  if (s.size() == 3 && s[1].attribute == "fluorescence") {
    FieldPlace p{FieldPlace::Kind::Fluorescence, s[2].attribute, nullptr, &o,
                 fluorescenceOf(o.params, name)};
    if (!o.materialRef.empty())
      p.refusal = label + ": uses the material '" + o.materialRef + "'; change scene.materials['" +
                  o.materialRef + "'] instead";
    return p;
  }
  if (s[1].attribute == "medium" && o.medium) {
    if (s.size() == 3 && s[2].attribute == "dye_peak")
      return {FieldPlace::Kind::DyePeak, "dye_peak", nullptr, &o,
              o.medium->params.getMutable<FluorescenceDesc>("fluorescence")};
    // A dye's model fields (its peak is the medium's dye_peak, a coefficient).
    const std::string& field = s.back().attribute;
    if (s.size() == 4 && s[2].attribute == "dye" && field != "peak_absorptance" &&
        field != "matrix" && field != "concentration")
      return {FieldPlace::Kind::Fluorescence, field, nullptr, &o,
              fluorescenceOf(o.medium->params, name)};
  }
  noField(name);
}

FieldValue optionalNumber(const std::optional<double>& v) {
  return v ? FieldValue(*v) : FieldValue();
}
FieldValue optionalSpectrum(const std::optional<SpectrumDesc>& v) {
  return v ? FieldValue(*v) : FieldValue();
}
template <size_t N>
FieldValue optionalNumbers(const std::optional<std::array<double, N>>& v) {
  return v ? FieldValue(std::vector<double>(v->begin(), v->end())) : FieldValue();
}

FieldValue settingField(const SettingsDesc& s, const std::string& leaf, const std::string& name) {
  if (leaf == "resolution") return std::vector<double>{double(s.width), double(s.height)};
  if (leaf == "mode") return std::string(renderModeName(s.mode));
  if (leaf == "spp") return double(s.samples);
  if (leaf == "seed") return double(s.seed);
  if (leaf == "depth") return double(s.depth);
  if (leaf == "bands") return s.bands.toString();
  if (leaf == "background") return optionalSpectrum(s.background);
  if (leaf == "illuminant") return optionalSpectrum(s.illuminant);
  if (leaf == "path") return s.outputPath;
  noField(name);
}

FieldValue cameraField(const CameraDesc& c, const std::string& leaf, const std::string& name) {
  if (leaf == "position") return c.position;
  if (leaf == "look_at") return c.lookAt;
  if (leaf == "up") return c.up;
  if (leaf == "fov") return c.intrinsics ? FieldValue() : FieldValue(c.fovDegrees);
  if (leaf == "intrinsics") return optionalNumbers(c.intrinsics);
  if (leaf == "distortion") return std::vector<double>(c.distortion.begin(), c.distortion.end());
  if (leaf == "thin_lens") return optionalNumbers(c.thinLens);
  if (leaf == "extrinsics") return optionalNumbers(c.extrinsics);
  noField(name);
}

FieldValue objectField(const ObjectDesc& o, const std::string& leaf, const std::string& name) {
  if (leaf == "emission") return optionalSpectrum(o.emission);
  if (leaf == "emission_scale") return o.emissionScale;
  if (leaf == "emission_at") return optionalNumber(o.emissionAt);
  if (leaf == "emission_quantity")
    return std::string(o.emissionAt ? "irradiance" : o.emissionFlux ? "flux" : "radiance");
  noField(name);
}

// A fluorescence model's field; its matrix and its concentration map read from their files
// when the scene names files.
FieldValue fluorescenceField(const FluorescenceDesc& f, const std::string& leaf,
                             const std::string& name) {
  if (leaf == "absorption_nm") return optionalNumber(f.absorptionNm);
  if (leaf == "stokes_nm") return optionalNumber(f.stokesNm);
  if (leaf == "width_nm") return optionalNumber(f.widthNm);
  if (leaf == "skew") return optionalNumber(f.skew);
  if (leaf == "quantum_yield") return optionalNumber(f.quantumYield);
  if (leaf == "peak_absorptance") return optionalNumber(f.peakAbsorptance);
  if (leaf == "absorptance" || leaf == "emission") {
    if (!f.spectra) return FieldValue();
    return leaf == "absorptance" ? f.spectra->absorptance : f.spectra->emission;
  }
  if (leaf == "matrix") {
    if (f.matrix) return f.matrix;
    if (!f.matrixCsv) return FieldValue();
    return std::make_shared<const MeasuredMatrix>(parseMeasuredMatrixCsv(
        readRegularFile(*f.matrixCsv, 64u << 20, "table file"), *f.matrixCsv));
  }
  if (leaf == "concentration") {
    if (f.concentration) return f.concentration;
    if (!f.concentrationCsv) return FieldValue();
    return std::make_shared<const ConcentrationMap>(parseConcentrationCsv(
        readRegularFile(*f.concentrationCsv, 64u << 20, "table file"), *f.concentrationCsv));
  }
  noField(name);
}

// ---- setting ----

template <class T>
const T& valueAs(const FieldValue& v, const std::string& name, const char* expected) {
  if (const T* x = std::get_if<T>(&v)) return *x;
  throw FieldTypeError(name + ": expected " + expected + ", found " +
                       (std::holds_alternative<std::monostate>(v) ? "None" : "another type"));
}

std::string integerText(double x) {
  return std::to_string(static_cast<long long>(x));
}

int integerIn(const FieldValue& v, const std::string& name, long long lo, long long hi) {
  const double x = valueAs<double>(v, name, "an int");
  if (!(x >= static_cast<double>(lo) && x <= static_cast<double>(hi)) || x != std::floor(x))
    throw Error(name + ": expected an int in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                "], found " + integerText(x));
  return static_cast<int>(x);
}

void setSetting(SettingsDesc& s, const std::string& leaf, const FieldValue& v,
                const std::string& name) {
  if (leaf == "resolution") {
    const auto& r = valueAs<std::vector<double>>(v, name, "(width, height)");
    if (r.size() != 2) throw Error(name + ": expected 2 ints, found " + std::to_string(r.size()));
    for (double x : r)
      if (!(x >= 1 && x <= kMaxResolution))
        throw Error(name + ": expected sizes in [1, 65536], found " + integerText(x));
    s.width = static_cast<int>(r[0]);
    s.height = static_cast<int>(r[1]);
  } else if (leaf == "mode") {
    const std::string& m = valueAs<std::string>(v, name, "a str");
    const auto mode = parseRenderMode(m);
    if (!mode) throw Error(name + ": expected rt, mcpt or spectral_mcpt, found '" + m + "'");
    s.mode = *mode;
  } else if (leaf == "spp") {
    s.samples = integerIn(v, name, 1, 1 << 30);
  } else if (leaf == "seed") {
    s.seed = static_cast<uint32_t>(integerIn(v, name, 0, 2147483647));
  } else if (leaf == "depth") {
    s.depth = integerIn(v, name, 0, 100000);
  } else if (leaf == "bands") {
    s.bands = Sensor::parse(valueAs<std::string>(v, name, "a str"), "bands");
    s.sensorFile.clear(); // no longer the file's sensor
    s.sensorCentres.clear();
  } else if (leaf == "background" || leaf == "illuminant") {
    std::optional<SpectrumDesc>& target = leaf == "background" ? s.background : s.illuminant;
    if (std::holds_alternative<std::monostate>(v))
      target.reset();
    else
      target = valueAs<SpectrumDesc>(v, name, "a spectrum");
  } else if (leaf == "path") {
    s.outputPath = valueAs<std::string>(v, name, "a str");
  } else {
    noField(name);
  }
}

std::vector<double> numbersOf(const FieldValue& v, const std::string& name, size_t n) {
  const auto& x = valueAs<std::vector<double>>(v, name, "numbers");
  if (n && x.size() != n)
    throw Error(name + ": expected " + std::to_string(n) + " numbers, found " +
                std::to_string(x.size()));
  return x;
}

// The camera with field `leaf` set, checked as the build checks it.
void setCamera(SceneDesc& d, const std::string& leaf, const FieldValue& v,
               const std::string& name) {
  CameraDesc c = d.camera;
  if ((leaf == "position" || leaf == "look_at") && c.extrinsics)
    throw Error(name + ": the camera is placed by <extrinsics>");
  if (leaf == "position") {
    c.position = valueAs<Vec3d>(v, name, "a point");
  } else if (leaf == "look_at") {
    c.lookAt = valueAs<Vec3d>(v, name, "a point");
  } else if (leaf == "up") {
    c.up = valueAs<Vec3d>(v, name, "a direction");
  } else if (leaf == "fov") {
    c.fovDegrees = valueAs<double>(v, name, "a number");
    c.intrinsics.reset();
  } else if (leaf == "intrinsics") {
    const auto k = numbersOf(v, name, 4);
    c.intrinsics = std::array<double, 4>{k[0], k[1], k[2], k[3]};
  } else if (leaf == "distortion") {
    const auto k = numbersOf(v, name, 0);
    if (k.size() < 4 || k.size() > 5) throw Error(name + ": expected k1, k2, p1, p2[, k3]");
    for (double x : k)
      if (!(std::abs(x) <= 1e4)) throw Error(name + ": expected coefficients within [-1e4, 1e4]");
    c.distortion = {};
    std::copy(k.begin(), k.end(), c.distortion.begin());
    c.distortionLoc = c.loc;
  } else if (leaf == "thin_lens") {
    if (std::holds_alternative<std::monostate>(v)) {
      c.thinLens.reset();
    } else {
      const auto k = numbersOf(v, name, 2);
      c.thinLens = std::array<double, 2>{k[0], k[1]};
    }
  } else if (leaf == "extrinsics") {
    if (std::holds_alternative<std::monostate>(v))
      throw Error(name + ": expected 12 numbers (r11 .. r33, t1, t2, t3); a camera placed by "
                         "extrinsics has no look-at form");
    const auto k = numbersOf(v, name, 12);
    c.extrinsics = std::array<double, 12>{};
    std::copy(k.begin(), k.end(), c.extrinsics->begin());
  } else {
    noField(name);
  }
  try {
    checkCameraDesc(c, d.settings.width, d.settings.height);
  } catch (const Error& e) {
    throw Error(name + ": " + e.what());
  }
  d.camera = c;
}

void setObjectField(ObjectDesc& o, const std::string& leaf, const FieldValue& v,
                    const std::string& name) {
  if (leaf == "emission") {
    if (std::holds_alternative<std::monostate>(v))
      o.emission.reset();
    else
      o.emission = valueAs<SpectrumDesc>(v, name, "a spectrum");
    return;
  }
  if (!o.emission) throw Error(name + ": the object emits no light");
  if (leaf == "emission_scale") {
    o.emissionScale = valueAs<double>(v, name, "a number");
  } else if (leaf == "emission_at") {
    if (std::holds_alternative<std::monostate>(v)) {
      o.emissionAt.reset();
    } else {
      o.emissionAt = valueAs<double>(v, name, "a number");
      o.emissionFlux = false;
    }
  } else if (leaf == "emission_quantity") {
    const std::string& q = valueAs<std::string>(v, name, "a str");
    if (q == "irradiance" && !o.emissionAt)
      throw Error(name + ": 'irradiance' needs a distance: set emission_at");
    if (q != "radiance" && q != "flux" && q != "irradiance")
      throw Error(name + ": expected 'radiance', 'flux' or 'irradiance', found '" + q + "'");
    if (q != "irradiance") o.emissionAt.reset();
    o.emissionFlux = q == "flux";
  } else {
    noField(name);
  }
}

// Refuses a model field where the fluorescence is not the parametric model: an imported EEM
// (only the yield and peak absorptance it was made absolute with) or a measured matrix.
void requireModelField(const FluorescenceDesc& f, const std::string& leaf,
                       const std::string& name) {
  if (leaf == "matrix" || leaf == "concentration") return;
  const bool spectral = leaf == "absorptance" || leaf == "emission";
  if (f.spectra) {
    if (spectral || leaf == "quantum_yield") return;
    throw Error(name + ": the fluorescence is given by its <absorptance> and <emission> "
                       "spectra; set them, or a model with set_fluorescence(...)");
  }
  if (spectral)
    throw Error(name + ": the fluorescence is not given by spectra (it is " +
                (f.eem                     ? "an imported EEM"
                 : f.matrixCsv || f.matrix ? "a measured matrix"
                                           : "the parametric model") +
                "); write <absorptance> and <emission> in the scene to give it so");
  if (f.eem) {
    if ((leaf == "quantum_yield" && f.eem->referenceFile.empty()) ||
        (leaf == "peak_absorptance" && !f.eem->absorptance))
      return;
    throw Error(name + ": the fluorescence is the EEM " + f.eem->file +
                (leaf == "quantum_yield" || leaf == "peak_absorptance"
                     ? " whose " + leaf + " comes from its <reference> or <absorptance>"
                     : std::string("; only quantum_yield and peak_absorptance of an EEM are set "
                                   "from Python")));
  }
  if (f.matrixCsv || f.matrix)
    throw Error(name + ": the fluorescence is a measured matrix" +
                (f.matrixCsv ? " (" + *f.matrixCsv + ")" : std::string()) +
                "; set a model with set_fluorescence(...) first");
}

void setFluorescenceField(FluorescenceDesc& f, const std::string& leaf, const FieldValue& v,
                          const std::string& name) {
  requireModelField(f, leaf, name);
  const bool none = std::holds_alternative<std::monostate>(v);
  if (leaf == "matrix") {
    auto m = valueAs<std::shared_ptr<const MeasuredMatrix>>(v, name, "a measured matrix");
    checkMeasuredMatrix(*m, name);
    FluorescenceDesc g;
    g.loc = f.loc;
    g.matrix = m;
    g.matrixDigest = measuredMatrixDigest(*m);
    f = g;
    return;
  }
  if (leaf == "concentration") {
    if (f.matrixCsv || f.matrix)
      throw Error(name + ": a concentration map needs the parametric model or an imported EEM, "
                         "found a measured matrix");
    f.concentration =
        none ? nullptr
             : valueAs<std::shared_ptr<const ConcentrationMap>>(v, name, "a concentration map");
    f.concentrationCsv.reset();
    return;
  }
  if (leaf == "absorptance" || leaf == "emission") {
    auto spectra = std::make_shared<DyeSpectra>(*f.spectra);
    (leaf == "absorptance" ? spectra->absorptance : spectra->emission) =
        valueAs<SpectrumDesc>(v, name, "a spectrum");
    f.spectra = spectra;
    return;
  }
  // None means "the default" only where there is one: the Stokes shift has none, and an
  // imported EEM's yield and peak absorptance are what make it absolute.
  if (none && (leaf == "stokes_nm" || leaf == "absorption_nm" || f.eem))
    throw FieldTypeError(name + ": expected a number (" +
                         (f.eem ? "the EEM " + f.eem->file + " is made absolute with it"
                                : std::string("the model has no default")) +
                         "), found None");
  const std::optional<double> x =
      none ? std::nullopt : std::optional<double>(valueAs<double>(v, name, "a number"));
  if (leaf == "absorption_nm") {
    f.absorptionNm = x;
    f.absorptionName.reset();
  } else if (leaf == "stokes_nm") {
    f.stokesNm = x;
  } else if (leaf == "width_nm") {
    f.widthNm = x;
  } else if (leaf == "skew") {
    f.skew = x;
  } else if (leaf == "quantum_yield") {
    f.quantumYield = x;
  } else if (leaf == "peak_absorptance") {
    f.peakAbsorptance = x;
  } else {
    noField(name);
  }
}

} // namespace

namespace {
// The key the steps of a name would have, declared or not.
std::string keyOfSteps(const std::vector<ParameterStep>& s) {
  const std::string& top = s[0].attribute;
  const std::string& leaf = s.back().attribute;
  if (s.size() == 1) return top;
  if (top == "camera") return "camera." + leaf;
  if (top == "spectra") return "spectrum." + leaf;
  if (s.size() == 2 && top == "objects") return "object." + leaf;
  if (leaf == "dye_peak") return "medium.dye_peak";
  if (s[s.size() - 2].attribute == "fluorescence" || s[s.size() - 2].attribute == "dye")
    return "fluorescence." + leaf;
  return "";
}
} // namespace

std::string sceneFieldKey(const std::string& name) {
  std::string key;
  try {
    key = keyOfSteps(parameterSteps(name));
  } catch (const Error&) {
    return "";
  }
  for (const FixedParameter& f : fixedParameters())
    if (key == f.key) return key;
  return "";
}

FieldValue sceneField(const SceneDesc& d, const std::string& name) {
  // Places are found on an editable scene; reading does not change it.
  SceneDesc& scene = const_cast<SceneDesc&>(d);
  const FieldPlace p = placeOf(scene, name);
  switch (p.kind) {
  case FieldPlace::Kind::Setting:
    return settingField(d.settings, p.leaf, name);
  case FieldPlace::Kind::Spectrum:
    return p.spectrum->spectrum;
  case FieldPlace::Kind::Camera:
    return cameraField(d.camera, p.leaf, name);
  case FieldPlace::Kind::Object:
    return objectField(*p.object, p.leaf, name);
  case FieldPlace::Kind::Fluorescence:
    return fluorescenceField(*p.fluorescence, p.leaf, name);
  case FieldPlace::Kind::DyePeak:
    return p.fluorescence ? optionalNumber(p.fluorescence->peakAbsorptance) : FieldValue();
  }
  noField(name);
}

std::string sceneFieldFile(const SceneDesc& d, const std::string& name) {
  const FieldPlace p = placeOf(const_cast<SceneDesc&>(d), name); // reading changes nothing
  if (p.kind != FieldPlace::Kind::Fluorescence) return "";
  const FluorescenceDesc& f = *p.fluorescence;
  if (p.leaf == "matrix" && !f.matrix && f.matrixCsv) return *f.matrixCsv;
  if (p.leaf == "concentration" && !f.concentration && f.concentrationCsv)
    return *f.concentrationCsv;
  return "";
}

void setSceneField(SceneDesc& d, const std::string& name, const FieldValue& v) {
  const FieldPlace p = placeOf(d, name);
  if (!p.refusal.empty()) throw Error(p.refusal);
  switch (p.kind) {
  case FieldPlace::Kind::Setting: {
    SettingsDesc s = d.settings;
    setSetting(s, p.leaf, v, name);
    d.settings = std::move(s);
    return;
  }
  case FieldPlace::Kind::Spectrum: {
    const SpectrumDesc& s = valueAs<SpectrumDesc>(v, name, "a spectrum");
    if (s.kind == SpectrumDesc::Kind::Texture)
      throw Error(name + ": expected a spectrum, found a texture");
    if (s.kind == SpectrumDesc::Kind::Name)
      throw Error(name + ": expected numbers or a CSV file (a named spectrum is defined by "
                         "values, not by another name)");
    p.spectrum->spectrum = s;
    return;
  }
  case FieldPlace::Kind::Camera:
    return setCamera(d, p.leaf, v, name);
  case FieldPlace::Kind::Object: {
    ObjectDesc o = *p.object;
    setObjectField(o, p.leaf, v, name);
    *p.object = std::move(o);
    return;
  }
  case FieldPlace::Kind::Fluorescence: {
    FluorescenceDesc f = *p.fluorescence;
    setFluorescenceField(f, p.leaf, v, name);
    *p.fluorescence = std::move(f);
    return;
  }
  case FieldPlace::Kind::DyePeak:
    if (!p.fluorescence) throw Error(name + ": the medium has no dye; use set_dye(...)");
    p.fluorescence->peakAbsorptance = valueAs<double>(v, name, "a number");
    return;
  }
}

} // namespace nx
