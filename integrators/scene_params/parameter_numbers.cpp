#include "integrators/scene_params/parameter_numbers.h"

#include <cmath>
#include <memory>
#include <optional>
#include <type_traits>

#include "accel/shape_kinds.h"
#include "core/error.h"
#include "core/params/array_values.h"
#include "core/params/concentration_map.h"
#include "core/triangle_mesh.h"
#include "integrators/scene_params/parameter_path.h"
#include "integrators/scene_params/scene_fields.h"
#include "integrators/scene_params/scene_parameter_list.h"
#include "spectra/reradiation_matrix.h"

namespace nx {
namespace {

// A parameter's value as far as its numbers go: a number, a colour, a point (a shape's or the
// camera's), a spectrum, a measured matrix, a concentration map, rows of reals or an affine
// transform.
using NumberedValue = std::variant<double, std::array<double, 4>, Vec3d, SpectrumDesc,
                                   std::shared_ptr<const MeasuredMatrix>,
                                   std::shared_ptr<const ConcentrationMap>, ArrayDesc, AffineDesc>;

// The ParameterSet holding kind parameter `name` (an object's shape or material, its medium's,
// a light's, a named material's) and its key there; throws for a field parameter's name, which
// scene_fields.h holds.
std::pair<ParameterSet*, std::string> kindParameter(SceneDesc& d, const std::string& name) {
  const std::vector<ParameterStep> s = parameterSteps(name);
  const std::string& top = s[0].attribute;
  const std::string& leaf = s.back().attribute;
  if (top == "objects" && (s.size() == 2 || (s.size() == 3 && s[1].attribute == "medium"))) {
    ObjectDesc& o = d.objects.at(std::get<size_t>(s[0].index));
    if (s.size() == 3 && o.medium) return {&o.medium->params, leaf};
    const ShapeKindSpec* kind = findShapeKind(o.shape);
    return {kind && shapeParameter(*kind, leaf) ? &o.geometry : &o.params, leaf};
  }
  if (top == "lights" && s.size() == 2)
    return {&d.lights.at(std::get<size_t>(s[0].index)).params, leaf};
  if (top == "materials" && s.size() == 2)
    for (NamedMaterialDesc& m : d.materials)
      if (m.id == std::get<std::string>(s[0].index)) return {&m.material.params, leaf};
  throw Error(name + ": has no numbers (not an appearance parameter)");
}

[[noreturn]] void notDifferentiable(const std::string& name, const std::string& found) {
  throw Error(name +
              ": not differentiable as given: expected a number, a point, a tabulated spectrum "
              "(wavelengths_nm, values) or a colour, found " +
              found +
              " (a named or built-in spectrum: set it as (wavelengths_nm, values) first, or "
              "differentiate its scale)");
}

// The value of `d`'s parameter `name`, or nullopt when it is not given.
std::optional<NumberedValue> valueOf(const SceneDesc& d, const std::string& name) {
  if (!sceneFieldKey(name).empty()) {
    const FieldValue v = sceneField(d, name);
    if (const double* x = std::get_if<double>(&v)) return *x;
    if (const auto* p = std::get_if<Vec3d>(&v)) return *p;
    if (const auto* s = std::get_if<SpectrumDesc>(&v)) return *s;
    if (const auto* m = std::get_if<std::shared_ptr<const MeasuredMatrix>>(&v)) {
      if (const std::string file = sceneFieldFile(d, name); !file.empty())
        notDifferentiable(name, "the matrix file " + file); // give it as numbers first
      return *m;
    }
    if (const auto* c = std::get_if<std::shared_ptr<const ConcentrationMap>>(&v)) return *c;
    return std::nullopt;
  }
  // Read through the editable lookup; reading changes nothing.
  const auto [set, key] = kindParameter(const_cast<SceneDesc&>(d), name);
  const Parameter* p = set->find(key);
  if (!p) return std::nullopt;
  if (const double* x = std::get_if<double>(&p->value)) return *x;
  if (const auto* c = std::get_if<std::array<double, 4>>(&p->value)) return *c;
  if (const auto* x = std::get_if<Vec3d>(&p->value)) return *x;
  if (const auto* s = std::get_if<SpectrumDesc>(&p->value)) return *s;
  if (const auto* a = std::get_if<ArrayDesc>(&p->value); a && a->reals) return *a;
  if (const auto* t = std::get_if<AffineDesc>(&p->value)) return *t;
  return std::nullopt; // no numbers (a name, a file, an index of refraction)
}

// Sets `d`'s parameter `name` to `v` (of the form valueOf gave).
void setValue(SceneDesc& d, const std::string& name, const NumberedValue& v) {
  if (!sceneFieldKey(name).empty()) // fields hold no colours
    return std::visit(
        [&](const auto& x) {
          if constexpr (std::is_constructible_v<FieldValue, decltype(x)>)
            setSceneField(d, name, FieldValue(x));
        },
        v);
  const auto [set, key] = kindParameter(d, name);
  const SourceLocation loc = set->locOf(key, SourceLocation{});
  if (const auto* x = std::get_if<double>(&v)) set->set({key, *x, loc});
  if (const auto* c = std::get_if<std::array<double, 4>>(&v)) set->set({key, *c, loc});
  if (const auto* x = std::get_if<Vec3d>(&v)) set->set({key, *x, loc});
  if (const auto* s = std::get_if<SpectrumDesc>(&v)) set->set({key, *s, loc});
  if (const auto* a = std::get_if<ArrayDesc>(&v)) set->set({key, *a, loc});
  if (const auto* t = std::get_if<AffineDesc>(&v)) set->set({key, *t, loc});
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

ParameterNumbers numbersOf(const NumberedValue& v, const std::string& name) {
  ParameterNumbers n;
  if (const double* x = std::get_if<double>(&v)) {
    n.values = {*x};
  } else if (const auto* c = std::get_if<std::array<double, 4>>(&v)) {
    n.form = ParameterNumbers::Form::List;
    n.values.assign(c->begin(), c->end());
  } else if (const auto* p = std::get_if<Vec3d>(&v)) {
    n.form = ParameterNumbers::Form::List;
    n.values = {p->x, p->y, p->z};
  } else if (const auto* s = std::get_if<SpectrumDesc>(&v)) {
    return spectrumNumbers(*s, name);
  } else if (const auto* a = std::get_if<ArrayDesc>(&v)) {
    n.form = ParameterNumbers::Form::Rows;
    n.values.assign(a->reals->begin(), a->reals->end());
    n.shape = {static_cast<long>(a->rows()), static_cast<long>(a->columns)};
  } else if (const auto* t = std::get_if<AffineDesc>(&v)) {
    // Rows of [m | t], as the transform's value reads: p -> m p + t.
    n.form = ParameterNumbers::Form::Rows;
    for (int r = 0; r < 3; ++r) {
      n.values.insert(n.values.end(), t->m[static_cast<size_t>(r)].begin(),
                      t->m[static_cast<size_t>(r)].end());
      n.values.push_back(r == 0 ? t->t.x : r == 1 ? t->t.y : t->t.z);
    }
    n.shape = {3, 4};
  } else if (const auto* m = std::get_if<std::shared_ptr<const MeasuredMatrix>>(&v)) {
    n.form = ParameterNumbers::Form::Matrix;
    n.values = (*m)->cells;
    n.shape = {static_cast<long>((*m)->excitationNm.size()),
               static_cast<long>((*m)->emissionNm.size())};
  } else {
    const ConcentrationMap& map = *std::get<std::shared_ptr<const ConcentrationMap>>(v);
    n.form = ParameterNumbers::Form::Concentration;
    n.values.assign(map.values.begin(), map.values.end());
    n.shape = {map.height, map.width};
  }
  return n;
}

// `current` with its numbers replaced by `v` (as many as it has); nullopt where one is refused.
std::optional<NumberedValue> withNumbers(const NumberedValue& current,
                                         const SceneParameterInfo& info,
                                         std::span<const double> v) {
  if (std::holds_alternative<double>(current)) {
    if (!std::isfinite(v[0]) || (info.range && !info.range->contains(v[0]))) return std::nullopt;
    return v[0];
  }
  if (std::holds_alternative<std::array<double, 4>>(current)) {
    std::array<double, 4> c{};
    const double hi = info.range ? info.range->hi : 1e12;
    for (size_t i = 0; i < 4; ++i) {
      if (i < 3 && !(v[i] >= 0 && v[i] <= hi)) return std::nullopt;
      c[i] = v[i];
    }
    return c;
  }
  if (std::holds_alternative<Vec3d>(current)) {
    for (size_t i = 0; i < 3; ++i)
      if (!std::isfinite(v[i]) || std::abs(v[i]) > 1e12) return std::nullopt;
    return Vec3d{v[0], v[1], v[2]};
  }
  if (std::holds_alternative<AffineDesc>(current)) {
    AffineDesc t;
    for (size_t r = 0; r < 3; ++r)
      for (size_t c = 0; c < 3; ++c) t.m[r][c] = v[4 * r + c];
    t.t = Vec3d(v[3], v[7], v[11]);
    for (double x : v)
      if (!std::isfinite(x) || std::abs(x) > kMaxMeshCoordinate) return std::nullopt;
    if (!t.keepsVolume()) return std::nullopt; // as the scene's reader refuses it
    return t;
  }
  if (const auto* a = std::get_if<ArrayDesc>(&current)) {
    for (double x : v) // float, and within the scene's coordinates
      if (!std::isfinite(x) || std::abs(x) > kMaxMeshCoordinate) return std::nullopt;
    try {
      return realRows(std::vector<float>(v.begin(), v.end()), a->columns);
    } catch (const Error&) {
      return std::nullopt;
    }
  }
  if (const auto* s = std::get_if<SpectrumDesc>(&current)) {
    SpectrumDesc out = *s;
    for (double x : v) // spectra (reflectances, emissions, coefficients) are not negative
      if (!std::isfinite(x) || x < 0) return std::nullopt;
    if (s->kind == SpectrumDesc::Kind::Number) {
      out.number = v[0];
    } else if (s->kind == SpectrumDesc::Kind::Pairs) {
      out.value.assign(v.begin(), v.end());
    } else {
      auto t = std::make_shared<SpectralTexels>(*s->texels);
      for (size_t i = 0; i < v.size(); ++i) {
        if (!(v[i] <= 1)) return std::nullopt;
        t->values[i] = static_cast<float>(v[i]);
      }
      t->digest = spectralTexelsDigest(*t);
      out.texels = t;
    }
    return out;
  }
  if (const auto* m = std::get_if<std::shared_ptr<const MeasuredMatrix>>(&current)) {
    auto changed = std::make_shared<MeasuredMatrix>(**m);
    changed->cells.assign(v.begin(), v.end());
    try {
      checkMeasuredMatrix(*changed, info.name);
    } catch (const Error&) {
      return std::nullopt;
    }
    return std::shared_ptr<const MeasuredMatrix>(changed);
  }
  const ConcentrationMap& map = *std::get<std::shared_ptr<const ConcentrationMap>>(current);
  try {
    return std::make_shared<const ConcentrationMap>(makeConcentrationMap(
        map.width, map.height, std::vector<float>(v.begin(), v.end()), info.name));
  } catch (const Error&) {
    return std::nullopt;
  }
}

} // namespace

ParameterNumbers parameterNumbers(const SceneDesc& d, const std::string& name) {
  const SceneParameterInfo info = sceneParameter(d, name);
  const std::optional<NumberedValue> v = valueOf(d, info.name);
  if (!v) notDifferentiable(info.name, "None (not given: the kind's default)");
  return numbersOf(*v, info.name);
}

bool setParameterNumbers(SceneDesc& d, const std::string& name, std::span<const double> values) {
  const SceneParameterInfo info = sceneParameter(d, name);
  const std::optional<NumberedValue> current = valueOf(d, info.name);
  if (!current) notDifferentiable(info.name, "None (not given: the kind's default)");
  const ParameterNumbers before = numbersOf(*current, info.name);
  if (values.size() != before.values.size())
    throw Error(info.name + ": expected " + std::to_string(before.values.size()) +
                " numbers, found " + std::to_string(values.size()));
  const std::optional<NumberedValue> next = withNumbers(*current, info, values);
  if (!next) return false;
  setValue(d, info.name, *next);
  return true;
}

} // namespace nx
