#include "integrators/scene_params/parameter_numbers.h"

#include <cmath>
#include <functional>
#include <memory>
#include <optional>

#include "accel/shape_kinds.h"
#include "core/error.h"
#include "core/file_text.h"
#include "core/params/concentration_map.h"
#include "integrators/scene_params/parameter_path.h"
#include "integrators/scene_params/scene_parameter_list.h"
#include "spectra/reradiation_matrix.h"

namespace nx {
namespace {

// Where a parameter's value is in a description: read and write it as a ParamValue (a
// number, a colour, a spectrum or, for a matrix or a concentration map, the fluorescence
// holding it).
struct ValueAccess {
  std::function<std::optional<ParamValue>()> get;
  std::function<void(ParamValue)> set;
  ParameterNumbers::Form matrixOrMap = ParameterNumbers::Form::Number; ///< else Number
};

ValueAccess inSet(ParameterSet& p, const std::string& key, const SourceLocation& loc) {
  return {[&p, key]() -> std::optional<ParamValue> {
            const Parameter* q = p.find(key);
            return q ? std::optional<ParamValue>(q->value) : std::nullopt;
          },
          [&p, key, loc](ParamValue v) {
            p.set({key, std::move(v), p.locOf(key, loc)});
          }};
}

ValueAccess inOptionalSpectrum(std::optional<SpectrumDesc>& s) {
  return {[&s]() -> std::optional<ParamValue> {
            return s ? std::optional<ParamValue>(*s) : std::nullopt;
          },
          [&s](ParamValue v) { s = std::get<SpectrumDesc>(std::move(v)); }};
}

ValueAccess inField(std::optional<double>& f) {
  return {[&f]() -> std::optional<ParamValue> {
            return f ? std::optional<ParamValue>(*f) : std::nullopt;
          },
          [&f](ParamValue v) { f = std::get<double>(v); }};
}

// A fluorescence model's field `field` ("stokes_nm", ...), its matrix or its concentration map.
ValueAccess inFluorescence(FluorescenceDesc& f, const std::string& field, const std::string& name) {
  if (field == "absorption_nm") return inField(f.absorptionNm);
  if (field == "stokes_nm") return inField(f.stokesNm);
  if (field == "width_nm") return inField(f.widthNm);
  if (field == "skew") return inField(f.skew);
  if (field == "quantum_yield") return inField(f.quantumYield);
  if (field == "peak_absorptance") return inField(f.peakAbsorptance);
  if (f.spectra && (field == "absorptance" || field == "emission")) {
    const bool absorptance = field == "absorptance";
    return {[&f, absorptance]() -> std::optional<ParamValue> {
              return ParamValue(absorptance ? f.spectra->absorptance : f.spectra->emission);
            },
            [&f, absorptance](ParamValue v) {
              auto s = std::make_shared<DyeSpectra>(*f.spectra);
              (absorptance ? s->absorptance : s->emission) = std::get<SpectrumDesc>(std::move(v));
              f.spectra = s;
            }};
  }
  ValueAccess a{[&f]() -> std::optional<ParamValue> { return ParamValue(f); },
                [&f](ParamValue v) { f = std::get<FluorescenceDesc>(std::move(v)); }};
  if (field == "matrix")
    a.matrixOrMap = ParameterNumbers::Form::Matrix;
  else if (field == "concentration")
    a.matrixOrMap = ParameterNumbers::Form::Concentration;
  else
    throw Error("no scene parameter named '" + name + "'");
  return a;
}

FluorescenceDesc& fluorescenceIn(ParameterSet& p, const std::string& name) {
  FluorescenceDesc* f = p.getMutable<FluorescenceDesc>("fluorescence");
  if (!f) throw Error(name + ": no fluorescence here");
  return *f;
}

// An object's parameter after "objects[i].": its shape's, emission's, material's or medium's.
ValueAccess inObject(ObjectDesc& o, const std::vector<ParameterStep>& s, const std::string& name) {
  const std::string& leaf = s[1].attribute;
  if (s.size() == 2) {
    if (leaf == "emission") return inOptionalSpectrum(o.emission);
    if (leaf == "emission_scale")
      return {[&o]() -> std::optional<ParamValue> { return ParamValue(o.emissionScale); },
              [&o](ParamValue v) { o.emissionScale = std::get<double>(v); }};
    const ShapeKindSpec* kind = findShapeKind(o.shape);
    if (kind && shapeParameter(*kind, leaf)) return inSet(o.geometry, leaf, o.loc);
    return inSet(o.params, leaf, o.loc);
  }
  if (leaf == "fluorescence" && s.size() == 3)
    return inFluorescence(fluorescenceIn(o.params, name), s[2].attribute, name);
  if (leaf == "medium" && o.medium) {
    MediumDesc& m = *o.medium;
    if (s.size() == 3 && s[2].attribute == "dye_peak")
      return inField(fluorescenceIn(m.params, name).peakAbsorptance);
    if (s.size() == 3) return inSet(m.params, s[2].attribute, m.loc);
    if (s.size() == 4 && s[2].attribute == "dye")
      return inFluorescence(fluorescenceIn(m.params, name), s[3].attribute, name);
  }
  throw Error("no scene parameter named '" + name + "'");
}

// Where `d`'s parameter `name` (listed by sceneParameters) is.
ValueAccess access(SceneDesc& d, const std::string& name) {
  const std::vector<ParameterStep> s = parameterSteps(name);
  const std::string& top = s[0].attribute;
  auto index = [&](const ParameterStep& step) { return std::get<size_t>(step.index); };
  auto key = [&](const ParameterStep& step) { return std::get<std::string>(step.index); };
  if (s.size() == 1 && top == "background") return inOptionalSpectrum(d.settings.background);
  if (top == "spectra" && s.size() == 2)
    for (NamedSpectrumDesc& n : d.spectra)
      if (n.name == key(s[0]))
        return {[&n]() -> std::optional<ParamValue> { return ParamValue(n.spectrum); },
                [&n](ParamValue v) { n.spectrum = std::get<SpectrumDesc>(std::move(v)); }};
  if (top == "objects") return inObject(d.objects.at(index(s[0])), s, name);
  if (top == "lights" && s.size() == 2) {
    LightDesc& l = d.lights.at(index(s[0]));
    return inSet(l.params, s[1].attribute, l.loc);
  }
  if (top == "materials")
    for (NamedMaterialDesc& m : d.materials)
      if (m.id == key(s[0])) {
        if (s.size() == 2) return inSet(m.material.params, s[1].attribute, m.loc);
        if (s.size() == 3 && s[1].attribute == "fluorescence")
          return inFluorescence(fluorescenceIn(m.material.params, name), s[2].attribute, name);
      }
  throw Error(name + ": has no numbers (not an appearance parameter)");
}

[[noreturn]] void notDifferentiable(const std::string& name, const std::string& found) {
  throw Error(name +
              ": not differentiable as given: expected a number, a tabulated spectrum "
              "(wavelengths_nm, values) or a colour, found " +
              found +
              " (a named or built-in spectrum: set it as (wavelengths_nm, values) first, or "
              "differentiate its scale)");
}

ParameterNumbers spectrumNumbers(const SpectrumDesc& s, const std::string& name) {
  ParameterNumbers n;
  switch (s.kind) {
  case SpectrumDesc::Kind::Number:
    n.values = {s.number};
    return n;
  case SpectrumDesc::Kind::Pairs:
    n.form = ParameterNumbers::Form::Table;
    n.values = s.value;
    return n;
  case SpectrumDesc::Kind::Texture:
    if (!s.texels) notDifferentiable(name, "the texture file " + s.texture);
    n.form = ParameterNumbers::Form::Texture;
    n.values.assign(s.texels->values.begin(), s.texels->values.end());
    n.shape = {s.texels->height, s.texels->width, static_cast<long>(s.texels->nm.size())};
    return n;
  case SpectrumDesc::Kind::Name:
    notDifferentiable(name, "the spectrum name '" + s.name + "'");
  case SpectrumDesc::Kind::CsvFile:
    notDifferentiable(name, "the table file " + s.path);
  }
  notDifferentiable(name, "a spectrum");
}

// The concentration map of `f` (read from its CSV file if it has one), or null.
std::shared_ptr<const ConcentrationMap> concentrationOf(const FluorescenceDesc& f) {
  if (f.concentration || !f.concentrationCsv) return f.concentration;
  return std::make_shared<const ConcentrationMap>(parseConcentrationCsv(
      readRegularFile(*f.concentrationCsv, 64u << 20, "table file"), *f.concentrationCsv));
}

ParameterNumbers numbersOf(const ParamValue& v, ParameterNumbers::Form matrixOrMap,
                           const std::string& name) {
  ParameterNumbers n;
  if (const double* x = std::get_if<double>(&v)) {
    n.values = {*x};
    return n;
  }
  if (const auto* c = std::get_if<std::array<double, 4>>(&v)) {
    n.form = ParameterNumbers::Form::List;
    n.values.assign(c->begin(), c->end());
    return n;
  }
  if (const auto* s = std::get_if<SpectrumDesc>(&v)) return spectrumNumbers(*s, name);
  if (const auto* f = std::get_if<FluorescenceDesc>(&v)) {
    n.form = matrixOrMap;
    if (matrixOrMap == ParameterNumbers::Form::Matrix && f->matrix) {
      n.values = f->matrix->cells;
      n.shape = {static_cast<long>(f->matrix->excitationNm.size()),
                 static_cast<long>(f->matrix->emissionNm.size())};
      return n;
    }
    if (matrixOrMap == ParameterNumbers::Form::Concentration) {
      const auto map = concentrationOf(*f);
      if (!map)
        throw Error(name + ": not differentiable: the surface has no concentration map (set "
                           "one, e.g. numpy.ones((32, 32)))");
      n.values.assign(map->values.begin(), map->values.end());
      n.shape = {map->height, map->width};
      return n;
    }
    notDifferentiable(name, "the matrix file " + f->matrixCsv.value_or("?"));
  }
  notDifferentiable(name, "a value of another type");
}

// `current` with its numbers replaced by `v` (as many as it has); nullopt where one is refused.
std::optional<ParamValue> withNumbers(const ParamValue& current, ParameterNumbers::Form form,
                                      const SceneParameterInfo& info, std::span<const double> v) {
  auto inRange = [&](double x) { return !info.range || info.range->contains(x); };
  if (std::holds_alternative<double>(current)) {
    if (!std::isfinite(v[0]) || !inRange(v[0])) return std::nullopt;
    return ParamValue(v[0]);
  }
  if (std::holds_alternative<std::array<double, 4>>(current)) {
    std::array<double, 4> c{};
    const double hi = info.range ? info.range->hi : 1e12;
    for (size_t i = 0; i < 4; ++i) {
      if (i < 3 && !(v[i] >= 0 && v[i] <= hi)) return std::nullopt;
      c[i] = v[i];
    }
    return ParamValue(c);
  }
  if (const auto* s = std::get_if<SpectrumDesc>(&current)) {
    SpectrumDesc out = *s;
    for (double x : v) // spectra (reflectances, emissions, coefficients) are not negative
      if (!std::isfinite(x) || x < 0) return std::nullopt;
    if (s->kind == SpectrumDesc::Kind::Number) {
      if (!(v[0] >= 0)) return std::nullopt;
      out.number = v[0];
    } else if (s->kind == SpectrumDesc::Kind::Pairs) {
      out.value.assign(v.begin(), v.end());
    } else {
      auto t = std::make_shared<SpectralTexels>(*s->texels);
      for (size_t i = 0; i < v.size(); ++i) {
        if (!(v[i] >= 0 && v[i] <= 1)) return std::nullopt;
        t->values[i] = static_cast<float>(v[i]);
      }
      t->digest = spectralTexelsDigest(*t);
      out.texels = t;
    }
    return ParamValue(out);
  }
  FluorescenceDesc f = std::get<FluorescenceDesc>(current);
  if (form == ParameterNumbers::Form::Matrix) {
    auto m = std::make_shared<MeasuredMatrix>(*f.matrix);
    m->cells.assign(v.begin(), v.end());
    try {
      checkMeasuredMatrix(*m, info.name);
    } catch (const Error&) {
      return std::nullopt;
    }
    f.matrix = m;
    f.matrixDigest = measuredMatrixDigest(*m);
    return ParamValue(f);
  }
  const auto map = concentrationOf(f);
  try {
    f.concentration = std::make_shared<const ConcentrationMap>(makeConcentrationMap(
        map->width, map->height, std::vector<float>(v.begin(), v.end()), info.name));
  } catch (const Error&) {
    return std::nullopt;
  }
  f.concentrationCsv.reset();
  return ParamValue(f);
}

} // namespace

ParameterNumbers parameterNumbers(const SceneDesc& d, const std::string& name) {
  const SceneParameterInfo info = sceneParameter(d, name);
  // Read through the same access as writing (on a copy: access takes an editable scene).
  SceneDesc copy = d;
  const ValueAccess a = access(copy, info.name);
  const std::optional<ParamValue> v = a.get();
  if (!v) notDifferentiable(info.name, "None (not given: the kind's default)");
  return numbersOf(*v, a.matrixOrMap, info.name);
}

bool setParameterNumbers(SceneDesc& d, const std::string& name, std::span<const double> values) {
  const SceneParameterInfo info = sceneParameter(d, name);
  const ValueAccess a = access(d, info.name);
  const std::optional<ParamValue> current = a.get();
  if (!current) notDifferentiable(info.name, "None (not given: the kind's default)");
  const ParameterNumbers before = numbersOf(*current, a.matrixOrMap, info.name);
  if (values.size() != before.values.size())
    throw Error(info.name + ": expected " + std::to_string(before.values.size()) +
                " numbers, found " + std::to_string(values.size()));
  std::optional<ParamValue> next = withNumbers(*current, a.matrixOrMap, info, values);
  if (!next) return false;
  a.set(std::move(*next));
  return true;
}

} // namespace nx
