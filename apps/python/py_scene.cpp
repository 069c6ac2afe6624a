// nxrender.Scene and its views (camera, objects, materials, fluorescence, lights).

#include "apps/python/py_scene.h"
#include "apps/python/py_scene_lists.h"
#include "apps/python/py_scene_tree.h"
#include "apps/python/py_scene_views.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <filesystem>

#include "accel/shape_kinds.h"
#include "apps/python/py_arguments.h"
#include "apps/python/py_parameters.h"
#include "apps/python/py_readonly.h"
#include "apps/python/py_scene_tree.h"
#include "core/error.h"
#include "core/file_text.h"
#include "core/hash.h"
#include "core/params/material_parameters.h"
#include "core/params/scene_limits.h"
#include "integrators/lights/light_kinds.h"
#include "integrators/materials/material_kind.h"
#include "integrators/media/medium_kinds.h"
#include "integrators/scene_reader.h"
#include "io/camera_checks.h"
#include "io/scene_state_text.h"
#include "io/scene_to_tree.h"
#include "spectra/reradiation_matrix.h"

namespace nxpy {
namespace {

py::object spectrumToPythonOpt(const std::optional<nx::SpectrumDesc>& s) {
  return s ? spectrumToPython(*s) : py::object(py::none());
}

void record(SceneState& s, const std::string& what, const py::handle& value) {
  s.edits.push_back(what + " = " + py::repr(value).cast<std::string>());
}

// Applies edit to a copy of the camera, checks the result as the scene build does (the same
// function), and only then stores it and records the edit: a refused value leaves the scene
// as it was.
template <typename Edit>
void editCamera(SceneState& s, const std::string& param, const py::handle& value, Edit edit) {
  nx::CameraDesc copy = s.desc.camera;
  edit(copy);
  try {
    nx::checkCameraDesc(copy, s.desc.settings.width, s.desc.settings.height);
  } catch (const nx::Error& e) {
    throw py::value_error(param + ": " + e.what());
  }
  s.desc.camera = copy;
  record(s, param, value);
}

nx::Vec3d pointArgument(const py::handle& value, const std::string& param) {
  const std::vector<double> v = numbersArgument(value, param.c_str(), 3);
  for (double x : v)
    if (std::abs(x) > nx::kMaxSceneCoordinate)
      throw py::value_error(param + ": expected coordinates within 1e12, found " +
                            py::str(py::float_(x)).cast<std::string>());
  return {v[0], v[1], v[2]};
}

py::tuple tupleOf(const nx::Vec3d& v) {
  return py::make_tuple(v.x, v.y, v.z);
}

// Refuses a parameter the material's kind does not take (its schema), as the loader does.
void requireKindTakes(const MaterialView& v, const char* name, const std::string& param) {
  const nx::MaterialKindSpec* kind = nx::findMaterialKind(v.get().material);
  if (!kind || kind->param(name)) return;
  nx::ParameterSet probe;
  probe.set({name, 0.0, v.loc()});
  try {
    nx::checkMaterialParameters(*kind, probe);
  } catch (const nx::Error& e) {
    const std::string m = e.what(), prefix = v.loc().str() + ": ";
    throw py::value_error(param + ": " + (m.rfind(prefix, 0) == 0 ? m.substr(prefix.size()) : m));
  }
}

// Sets (None: removes) one declared parameter of a material, checked by its type, its range
// and the kind's schema; the names it excludes are removed.
void setMaterialParameter(const MaterialView& v, const nx::ParamSpec& spec, const py::handle& value,
                          const std::string& param) {
  nx::MaterialDesc& d = v.editable();
  if (value.is_none()) {
    d.params.erase(spec.name);
    return;
  }
  requireKindTakes(v, spec.name, param);
  d.params.set({spec.name, parameterFromPython(spec, value, param, v.loc()), v.loc()});
  nx::forEachWord(spec.excludes, [&](const std::string& x) { d.params.erase(x); });
}

// A measured matrix as Python arrays: (excitation_nm, emission_nm, values) with values of shape
// (excitation, emission).
py::object matrixToPython(const nx::MeasuredMatrix& m) {
  py::array_t<double> values({m.excitationNm.size(), m.emissionNm.size()});
  std::copy(m.cells.begin(), m.cells.end(), values.mutable_data());
  return py::make_tuple(py::array_t<double>(m.excitationNm.size(), m.excitationNm.data()),
                        py::array_t<double>(m.emissionNm.size(), m.emissionNm.data()), values);
}

// Gives a material a measured matrix from Python arrays (replacing any fluorescence), checked
// as a CSV matrix is; the edit is recorded with a digest of the content (a numpy repr elides).
void setMeasuredMatrix(const MaterialView& v, const py::handle& value, const std::string& param) {
  nx::MaterialDesc& d = v.editable();
  requireKindTakes(v, "fluorescence", param);
  if (!(py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) || py::len(value) != 3)
    throw py::type_error(param + ": expected (excitation_nm, emission_nm, values), found " +
                         typeName(value));
  auto m = std::make_shared<nx::MeasuredMatrix>();
  m->source = param;
  m->excitationNm = numberListArgument(value[py::int_(0)], (param + "[0]").c_str(), 2);
  m->emissionNm = numberListArgument(value[py::int_(1)], (param + "[1]").c_str(), 2);
  const auto cells =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value[py::int_(2)]);
  if (!cells || cells.ndim() != 2)
    throw py::type_error(param + "[2]: expected a 2-d array of values (excitation, emission)");
  if (static_cast<size_t>(cells.shape(0)) != m->excitationNm.size() ||
      static_cast<size_t>(cells.shape(1)) != m->emissionNm.size())
    throw py::value_error(param + "[2]: expected shape (" + std::to_string(m->excitationNm.size()) +
                          ", " + std::to_string(m->emissionNm.size()) + "), found (" +
                          std::to_string(cells.shape(0)) + ", " + std::to_string(cells.shape(1)) +
                          ")");
  m->cells.assign(cells.data(), cells.data() + cells.size());
  try {
    nx::checkMeasuredMatrix(*m, param);
  } catch (const nx::Error& e) {
    throw py::value_error(e.what());
  }
  nx::FluorescenceDesc f;
  f.loc = v.loc();
  f.matrix = m;
  f.matrixDigest = nx::measuredMatrixDigest(*m);
  d.params.set({"fluorescence", f, v.loc()});
  v.s->edits.push_back(param + " = <matrix " + std::to_string(m->excitationNm.size()) + "x" +
                       std::to_string(m->emissionNm.size()) + " digest " +
                       std::to_string(nx::fnv1a64(nx::canonicalText(nx::ParamValue(f)))) + ">");
}

// One property per parameter any kind in `kinds` declares (the first declaration of a name; a
// lights' or media's TakenParameter list), except those with views of their own (`skip`): read
// as its Python form (None: not given, the kind's default); set checked by its type and range,
// refused where the item's kind does not take it; None removes it (refused if required). A
// new spectrum NAME stands alone: it removes NAME_scale and NAME_at.
template <class View, class Kinds>
void bindTakenParameters(py::class_<View>& c, const Kinds& kinds, nx::ParamType skip) {
  std::vector<std::string> names;
  for (const auto& kind : kinds)
    for (const nx::TakenParameter& tp : kind.params()) {
      if (tp.spec.type == skip ||
          std::find(names.begin(), names.end(), tp.spec.name) != names.end())
        continue;
      names.push_back(tp.spec.name);
      const std::string name = tp.spec.name;
      c.def_property(
          tp.spec.name,
          [name](const View& v) -> py::object {
            const nx::Parameter* q = v.params().find(name);
            return q ? parameterToPython(q->value) : py::object(py::none());
          },
          [name](const View& v, const py::object& value) {
            const std::string param = v.label() + "." + name;
            const nx::TakenParameter* decl = v.declared(name);
            if (!decl)
              throw py::value_error(param + ": " + v.kindText() + " takes no <" + name + ">");
            nx::ParameterSet& p = v.params();
            if (value.is_none()) {
              if (decl->required) throw py::value_error(param + ": " + v.kindText() + " needs it");
              p.erase(name);
            } else {
              p.set({name, parameterFromPython(decl->spec, value, param, v.loc()),
                     p.locOf(name, v.loc())});
              if (decl->spec.type == nx::ParamType::Spectrum)
                p.erase(name + "_scale"), p.erase(name + "_at");
            }
            record(v.state(), param, value);
          },
          tp.spec.doc);
    }
}

// The three corner parameters of a triangle or a quad (their `vertices` together), if it is one.
std::optional<std::array<const char*, 3>> cornerNames(const std::string& shape) {
  if (shape == nx::TriangleShapeKind::kName) return std::array<const char*, 3>{"vA", "vB", "vC"};
  if (shape == nx::QuadShapeKind::kName)
    return std::array<const char*, 3>{"origin", "edge_u", "edge_v"};
  return std::nullopt;
}

// The parameter `name` of a shape kind, or ValueError naming the kinds that take it.
const nx::ShapeParameter& shapeParameterOf(const nx::ShapeKindSpec& kind, const std::string& name,
                                           const std::string& param) {
  if (const nx::ShapeParameter* decl = nx::shapeParameter(kind, name)) return *decl;
  std::vector<std::string> takers;
  for (const nx::ShapeKindSpec& k : nx::shapeKinds())
    if (nx::shapeParameter(k, name)) takers.push_back(std::string("a ") + k.name);
  throw py::value_error(param + ": a " + std::string(kind.name) + " takes no " + name + " (" +
                        nx::listWithOr(takers) + " does)");
}

// Sets (None: removes) parameters of an object's shape together, each checked by its type and
// range (the names it excludes removed), then all by the kind (shapeProblem: a required one, a
// value's own check, the parameters together): a refused change leaves the object as it was.
void setShapeParameters(const ObjectView& o,
                        const std::vector<std::pair<std::string, py::object>>& values) {
  nx::ObjectDesc& d = o.get();
  const nx::ShapeKindSpec& kind = *nx::findShapeKind(d.shape);
  nx::ParameterSet next = d.geometry;
  for (const auto& [name, value] : values) {
    const std::string param = o.label() + "." + name;
    const nx::ShapeParameter& decl = shapeParameterOf(kind, name, param);
    if (value.is_none()) {
      next.erase(name);
      continue;
    }
    next.set(
        {name, parameterFromPython(decl.spec, value, param, d.loc), d.geometry.locOf(name, d.loc)});
    nx::forEachWord(decl.spec.excludes, [&](const std::string& x) { next.erase(x); });
  }
  if (const auto problem = nx::shapeProblem(kind, next))
    throw py::value_error(o.label() + "." +
                          (values.size() == 1 ? values[0].first : std::string("update")) +
                          ": expected " + problem->expected + ", found " + problem->found);
  d.geometry = std::move(next);
}

// A optional<double> field of a fluorescence model (a material's or a dye's), with its range.
template <typename View>
void bindFluorescenceField(py::class_<View>& c, const char* name,
                           std::optional<double> nx::FluorescenceDesc::*field,
                           const nx::ParameterRange& range, const char* doc) {
  c.def_property(
      name,
      [field](const View& f) -> py::object {
        const auto& v = f.get().*field;
        return v ? py::object(py::float_(*v)) : py::object(py::none());
      },
      [field, name, range](const View& f, const py::object& value) {
        nx::FluorescenceDesc& d = f.editable(name);
        const std::string param = f.prefix() + "." + name;
        // None means "the default" only where there is one: the Stokes shift has none, and an
        // imported EEM's yield and peak absorptance are what make it absolute (a None was
        // recorded, then the build read an empty value).
        const bool required = std::string(name) == "stokes_nm" || d.eem;
        if (value.is_none() && required)
          throw py::type_error(param + ": expected a number (" +
                               (d.eem ? "the EEM " + d.eem->file + " is made absolute with it"
                                      : std::string("the model has no default")) +
                               "), found None");
        if (value.is_none())
          d.*field = std::nullopt;
        else
          d.*field = rangedArgument(value, param, range);
        record(f.state(), param, value);
      },
      doc);
}

// The model's fields both a material's fluorescence and a dye have.
template <typename View>
void bindFluorescenceModel(py::class_<View>& c) {
  c.def_property(
      "absorption_nm",
      [](const View& f) -> py::object {
        const auto& d = f.get();
        return d.absorptionNm ? py::object(py::float_(*d.absorptionNm)) : py::object(py::none());
      },
      [](const View& f, const py::object& value) {
        nx::FluorescenceDesc& d = f.editable("absorption_nm");
        const std::string param = f.prefix() + ".absorption_nm";
        d.absorptionNm = rangedArgument(value, param, nx::kAbsorptionRange);
        d.absorptionName.reset();
        record(f.state(), param, value);
      },
      "Absorption peak in nm (None when given by a colour name)");
  c.def_property_readonly(
      "absorption",
      [](const View& f) -> py::object {
        const auto& d = f.get();
        return d.absorptionName ? py::object(py::str(*d.absorptionName)) : py::object(py::none());
      },
      "Absorption colour name, if the scene gave one");
  bindFluorescenceField(c, "stokes_nm", &nx::FluorescenceDesc::stokesNm, nx::kStokesRange,
                        "Stokes shift in nm (emission peak minus absorption peak)");
  bindFluorescenceField(c, "width_nm", &nx::FluorescenceDesc::widthNm, nx::kWidthRange,
                        "Width of the absorption and emission bands in nm (None: default)");
  bindFluorescenceField(c, "skew", &nx::FluorescenceDesc::skew, nx::kSkewRange,
                        "Skew magnitude of the bands (None: default)");
  bindFluorescenceField(c, "quantum_yield", &nx::FluorescenceDesc::quantumYield, nx::kYieldRange,
                        "Quantum yield in [0, 1] (None: default)");
}

// The parametric fluorescence model's arguments (set_fluorescence, set_dye), checked; `p`
// prefixes the parameter names in errors.
nx::FluorescenceDesc fluorescenceModel(const std::string& p, const nx::SourceLocation& loc,
                                       const py::object& absorptionNm, const py::object& stokesNm,
                                       const py::object& widthNm, const py::object& skew,
                                       const py::object& quantumYield) {
  nx::FluorescenceDesc f;
  f.loc = loc;
  f.absorptionNm = rangedArgument(absorptionNm, p + "absorption_nm", nx::kAbsorptionRange);
  f.stokesNm = rangedArgument(stokesNm, p + "stokes_nm", nx::kStokesRange);
  if (!widthNm.is_none()) f.widthNm = rangedArgument(widthNm, p + "width_nm", nx::kWidthRange);
  if (!skew.is_none()) f.skew = rangedArgument(skew, p + "skew", nx::kSkewRange);
  if (!quantumYield.is_none())
    f.quantumYield = rangedArgument(quantumYield, p + "quantum_yield", nx::kYieldRange);
  return f;
}

// What Scene() is: the settings and camera a scene needs, nothing in it.
nx::SceneTree emptySceneTree() {
  using D = nx::SceneTree::Dict;
  using L = nx::SceneTree::List;
  return D{{"settings", D{{"xres", 64.0}, {"yres", 64.0}, {"mode", std::string("spectral_mcpt")}}},
           {"camera", D{{"position", L{0.0, 0.0, -5.0}}, {"look_at", L{0.0, 0.0, 0.0}}}}};
}

SceneState loadState(const std::string& text, const std::string& name) {
  SceneState st;
  st.desc = nx::parseScene(text, name);
  return st;
}

} // namespace

nx::SceneDesc sceneForRendering(const SceneState& state) {
  nx::SceneDesc d = state.desc;
  // The key follows the state: a no-op edit, or 0.4 -> 0.3 -> 0.4, keeps the file's key, and a
  // scene edited into another file's state takes that file's.
  d.textDigest = nx::sceneStateDigest(d);
  return d;
}

std::string editsText(const SceneState& state) {
  std::string out;
  for (const std::string& e : state.edits) out += (out.empty() ? "" : "; ") + e;
  return out;
}

namespace {

// nxrender.Fluorescence.
void bindFluorescenceClass(py::module_& m) {
  py::class_<FluorescenceView> fl(m, "Fluorescence",
                                  "The fluorescence of a material (the re-radiation matrix's "
                                  "parameters; docs/fluorescence.md)");
  bindFluorescenceModel(fl);
  bindFluorescenceField(fl, "peak_absorptance", &nx::FluorescenceDesc::peakAbsorptance,
                        nx::kPeakRange, "Absorptance at the absorption peak (None: default)");
  fl.def_property_readonly(
      "matrix_file",
      [](const FluorescenceView& f) -> py::object {
        const auto& d = f.get();
        return d.matrixCsv ? py::object(py::str(*d.matrixCsv)) : py::object(py::none());
      },
      "The measured matrix's CSV file, if it was read from one");
  fl.def_property_readonly(
      "eem_file",
      [](const FluorescenceView& f) -> py::object {
        const auto& d = f.get();
        return d.eem ? py::object(py::str(d.eem->file)) : py::object(py::none());
      },
      "The imported EEM's CSV file, if the fluorescence is one (docs/eem-import.md)");
  fl.def_property(
      "matrix",
      [](const FluorescenceView& f) -> py::object {
        const auto& d = f.get();
        if (d.matrix) return matrixToPython(*d.matrix);
        if (!d.matrixCsv) return py::none();
        nx::MeasuredMatrix read;
        try {
          read = nx::parseMeasuredMatrixCsv(
              nx::readRegularFile(*d.matrixCsv, 64u << 20, "table file"), *d.matrixCsv);
        } catch (const nx::Error& e) {
          throw py::value_error(f.m.label() + ".fluorescence.matrix: " + e.what());
        }
        return matrixToPython(read);
      },
      [](const FluorescenceView& f, const py::object& value) {
        setMeasuredMatrix(f.m, value, f.m.label() + ".fluorescence.matrix");
      },
      "The measured matrix (excitation_nm, emission_nm, values[excitation, emission]) as numpy "
      "arrays, or None for the parametric model; set it the same way (checked like a CSV's)");
  fl.def_property(
      "concentration",
      [](const FluorescenceView& f) -> py::object {
        const auto& d = f.get();
        std::shared_ptr<const nx::ConcentrationMap> map = d.concentration;
        if (!map && d.concentrationCsv) {
          try {
            map = std::make_shared<const nx::ConcentrationMap>(nx::parseConcentrationCsv(
                nx::readRegularFile(*d.concentrationCsv, 64u << 20, "table file"),
                *d.concentrationCsv));
          } catch (const nx::Error& e) {
            throw py::value_error(f.prefix() + ".concentration: " + e.what());
          }
        }
        if (!map) return py::none();
        py::array_t<float> a({map->height, map->width});
        std::copy(map->values.begin(), map->values.end(), a.mutable_data());
        return a;
      },
      [](const FluorescenceView& f, const py::object& value) {
        const std::string param = f.prefix() + ".concentration";
        const nx::FluorescenceDesc& current = f.get();
        if (current.matrixCsv || current.matrix)
          throw py::value_error(param + ": a concentration map needs the parametric model or an "
                                        "imported EEM, found a measured matrix");
        if (value.is_none()) {
          nx::FluorescenceDesc& d = f.get();
          (void)f.m.editable();
          d.concentration.reset();
          d.concentrationCsv.reset();
          record(f.state(), param, value);
          return;
        }
        const py::array_t<double, py::array::c_style | py::array::forcecast> a =
            py::module_::import("numpy").attr("asarray")(value, "float64");
        if (a.ndim() != 2)
          throw py::value_error(param + ": expected values[height, width], found an array of " +
                                std::to_string(a.ndim()) + " axes");
        std::vector<float> values(a.data(), a.data() + a.size());
        std::shared_ptr<const nx::ConcentrationMap> map;
        try {
          map = std::make_shared<const nx::ConcentrationMap>(
              nx::makeConcentrationMap(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)),
                                       std::move(values), param));
        } catch (const nx::Error& e) {
          throw py::value_error(e.what());
        }
        nx::FluorescenceDesc& d = f.get();
        (void)f.m.editable();
        d.concentration = map;
        d.concentrationCsv.reset();
        f.state().edits.push_back(param + " = <map " + std::to_string(map->height) + "x" +
                                  std::to_string(map->width) + " digest " +
                                  std::to_string(map->digest) + ">");
      },
      "The dye's relative concentration over the surface: values[height, width] in [0, 1] "
      "(row 0 at the top; bilinear by the hit's uv) scaling its absorptance, or None (1 "
      "everywhere); read from a <concentration> CSV file or set as numbers");
  fl.def("__repr__", [](const FluorescenceView& f) {
    const auto& d = f.get();
    if (d.matrixCsv) return "<nxrender.Fluorescence matrix=" + *d.matrixCsv + ">";
    if (d.matrix) return std::string("<nxrender.Fluorescence matrix (from arrays)>");
    return "<nxrender.Fluorescence absorption=" +
           (d.absorptionNm ? std::to_string(*d.absorptionNm) + " nm" : *d.absorptionName) +
           ", stokes=" + std::to_string(d.stokesNm.value_or(0)) + " nm>";
  });
}

// nxrender.Material: its kind and one property per declared parameter.
void bindMaterialClass(py::module_& m) {
  py::class_<MaterialView> mat(m, "Material",
                               "A material's parameters (an object's or a named one): a "
                               "property per parameter of the scene format "
                               "(docs/reference/materials.md)");
  mat.def_property_readonly(
      "kind", [](const MaterialView& v) { return v.get().material; },
      "matte, metal, plastic, mirror, glass, ...");
  // One property per declared parameter: read as its Python form (None: not given, the
  // kind's default), set checked by its type and range, None removes it.
  for (const nx::ParamSpec& spec : nx::materialParameters()) {
    if (spec.type == nx::ParamType::Fluorescence) continue; // a view of its own, below
    const nx::ParamSpec* sp = &spec;
    mat.def_property(
        spec.name,
        [sp](const MaterialView& v) -> py::object {
          const nx::Parameter* q = v.get().params.find(sp->name);
          return q ? parameterToPython(q->value) : py::object(py::none());
        },
        [sp](const MaterialView& v, const py::object& value) {
          const std::string param = v.label() + "." + sp->name;
          setMaterialParameter(v, *sp, value, param);
          // A texture's numbers are recorded by their digest (a numpy repr elides them).
          const auto* t = v.get().params.get<nx::SpectrumDesc>(sp->name);
          if (t && t->texels)
            v.s->edits.push_back(param + " = <texture " + std::to_string(t->texels->height) + "x" +
                                 std::to_string(t->texels->width) + "x" +
                                 std::to_string(t->texels->nm.size()) + " digest " +
                                 std::to_string(t->texels->digest) + ">");
          else
            record(*v.s, param, value);
        },
        spec.doc);
  }
  mat.def_property(
         "fluorescence",
         [](const MaterialView& v) -> py::object {
           if (!v.get().params.has("fluorescence")) return py::none();
           return py::cast(FluorescenceView{v});
         },
         [](const MaterialView& v, const py::object& value) {
           if (!value.is_none())
             throw py::type_error(v.label() +
                                  ".fluorescence: expected None (to remove it); give a model "
                                  "with set_fluorescence(...)");
           v.editable().params.erase("fluorescence");
           record(*v.s, v.label() + ".fluorescence", value);
         },
         "The fluorescence (None: none); assign None to remove it")
      .def(
          "set_fluorescence",
          [](const MaterialView& v, const py::object& absorptionNm, const py::object& stokesNm,
             const py::object& widthNm, const py::object& skew, const py::object& quantumYield,
             const py::object& peakAbsorptance) {
            nx::MaterialDesc& d = v.editable();
            const std::string p = v.label() + ".set_fluorescence: ";
            requireKindTakes(v, "fluorescence", v.label() + ".set_fluorescence");
            nx::FluorescenceDesc f =
                fluorescenceModel(p, v.loc(), absorptionNm, stokesNm, widthNm, skew, quantumYield);
            if (!peakAbsorptance.is_none())
              f.peakAbsorptance =
                  rangedArgument(peakAbsorptance, p + "peak_absorptance", nx::kPeakRange);
            d.params.set({"fluorescence", f, v.loc()});
            v.s->edits.push_back(v.label() + ".set_fluorescence(" +
                                 py::repr(py::make_tuple(absorptionNm, stokesNm, widthNm, skew,
                                                         quantumYield, peakAbsorptance))
                                     .cast<std::string>() +
                                 ")");
            return FluorescenceView{v};
          },
          py::arg("absorption_nm"), py::arg("stokes_nm"), py::arg("width_nm") = py::none(),
          py::arg("skew") = py::none(), py::arg("quantum_yield") = py::none(),
          py::arg("peak_absorptance") = py::none(),
          "Gives the material a fluorescence model (replacing any); returns it")
      .def(
          "set_fluorescence_matrix",
          [](const MaterialView& v, const py::object& excitationNm, const py::object& emissionNm,
             const py::object& values) {
            setMeasuredMatrix(v, py::make_tuple(excitationNm, emissionNm, values),
                              v.label() + ".fluorescence.matrix");
            return FluorescenceView{v};
          },
          py::arg("excitation_nm"), py::arg("emission_nm"), py::arg("values"),
          "Gives the material a measured Donaldson matrix from arrays (values[excitation, "
          "emission] in [0, 1], as a CSV matrix's cells), replacing any fluorescence; returns it")
      .def_property(
          "alpha_uv",
          [](const MaterialView& v) -> py::object {
            const auto& p = v.get().params;
            if (!p.has("alpha_u") || !p.has("alpha_v")) return py::none();
            return py::make_tuple(*p.number("alpha_u"), *p.number("alpha_v"));
          },
          [](const MaterialView& v, const py::object& value) {
            const std::string param = v.label() + ".alpha_uv";
            const std::vector<double> uv = numbersArgument(value, param.c_str(), 2);
            setMaterialParameter(v, *nx::materialParameter("alpha_u"), py::float_(uv[0]), param);
            setMaterialParameter(v, *nx::materialParameter("alpha_v"), py::float_(uv[1]), param);
            record(*v.s, param, value);
          },
          "Anisotropic GGX roughness (alpha_u, alpha_v), or None")
      .def("__repr__", [](const MaterialView& v) {
        return "<nxrender.Material " + v.label() + " " + v.get().material + ">";
      });
}

// nxrender.Dye and nxrender.Medium.
void bindMediumClasses(py::module_& m) {
  py::class_<DyeView> dye(m, "Dye",
                          "The fluorescent dye dissolved in a medium (the parametric model; its "
                          "peak absorption coefficient is the medium's dye_peak)");
  bindFluorescenceModel(dye);

  py::class_<MediumView> med(m, "Medium",
                             "The participating medium inside a sphere or closed mesh "
                             "(docs/media.md); coefficients per scene unit of length");
  bindTakenParameters(med, nx::mediumKinds(), nx::ParamType::Dye);
  med.def_property_readonly(
         "kind", [](const MediumView& v) { return v.get().kind; }, "homogeneous")
      .def_property_readonly(
          "dye",
          [](const MediumView& v) -> py::object {
            return v.get().params.has("fluorescence") ? py::cast(DyeView{v})
                                                      : py::object(py::none());
          },
          "The dye dissolved in it (None: none; set_dye(...) adds one)")
      .def_property(
          "dye_peak",
          [](const MediumView& v) -> py::object {
            const auto* f = v.get().params.get<nx::FluorescenceDesc>("fluorescence");
            return f && f->peakAbsorptance ? py::object(py::float_(*f->peakAbsorptance))
                                           : py::object(py::none());
          },
          [](const MediumView& v, const py::object& value) {
            auto* f = v.get().params.getMutable<nx::FluorescenceDesc>("fluorescence");
            const std::string param = v.label() + ".dye_peak";
            if (!f) throw py::value_error(param + ": the medium has no dye; use set_dye(...)");
            f->peakAbsorptance = rangedArgument(value, param, nx::kPeakCoefficientRange);
            record(*v.o.s, param, value);
          },
          "The dye's peak absorption coefficient per unit length (None: no dye)")
      .def(
          "set_dye",
          [](const MediumView& v, const py::object& absorptionNm, const py::object& stokesNm,
             const py::object& peak, const py::object& widthNm, const py::object& skew,
             const py::object& quantumYield) {
            const std::string p = v.label() + ".set_dye: ";
            nx::FluorescenceDesc f = fluorescenceModel(p, v.o.get().loc, absorptionNm, stokesNm,
                                                       widthNm, skew, quantumYield);
            f.peakAbsorptance = rangedArgument(peak, p + "peak", nx::kPeakCoefficientRange);
            v.get().params.set({"fluorescence", f, v.get().loc});
            v.o.s->edits.push_back(
                v.label() + ".set_dye(" +
                py::repr(py::make_tuple(absorptionNm, stokesNm, peak, widthNm, skew, quantumYield))
                    .cast<std::string>() +
                ")");
          },
          py::arg("absorption_nm"), py::arg("stokes_nm"), py::arg("peak"),
          py::arg("width_nm") = py::none(), py::arg("skew") = py::none(),
          py::arg("quantum_yield") = py::none(),
          "Dissolves a fluorescent dye (the parametric model; peak: its peak absorption "
          "coefficient per unit length), replacing any")
      .def("remove_dye",
           [](const MediumView& v) {
             v.get().params.erase("fluorescence");
             v.o.s->edits.push_back(v.label() + ".remove_dye()");
           })
      .def("__repr__", [](const MediumView& v) { return "<nxrender.Medium " + v.label() + ">"; });
}

// nxrender.Object: its structure, medium, material and emission (bindObjectShape: the rest).
py::class_<ObjectView> bindObjectClass(py::module_& m) {
  py::class_<ObjectView> object(m, "Object",
                                "One object of the scene: a shape kind's parameters (a property "
                                "each, docs/reference/shapes.md) and its appearance");
  object
      .def_property(
          "medium",
          [](const ObjectView& o) -> py::object {
            return o.get().medium ? py::cast(MediumView{o}) : py::object(py::none());
          },
          [](const ObjectView& o, const py::object& value) {
            if (!value.is_none())
              throw py::type_error(o.label() +
                                   ".medium: expected None (to remove it); fill the object "
                                   "with set_medium(...)");
            o.get().medium.reset();
            record(*o.s, o.label() + ".medium", value);
          },
          "The medium inside a sphere or closed mesh (None: none); assign None to remove it")
      .def(
          "update",
          [](const ObjectView& o, const py::kwargs& values) {
            std::vector<std::pair<std::string, py::object>> v;
            for (const auto& [k, x] : values)
              v.emplace_back(k.cast<std::string>(), py::reinterpret_borrow<py::object>(x));
            setShapeParameters(o, v);
            for (const auto& [k, x] : v) record(*o.s, o.label() + "." + k, x);
          },
          "Sets several shape parameters at once, checked together (e.g. a mesh's vertices, "
          "faces, normals and uv: o.update(vertices=V, faces=F)); None removes one")
      .def(
          "set_medium",
          [](const ObjectView& o, const py::object& sigmaA, const py::object& sigmaS,
             const py::object& g) {
            if (!nx::findShapeKind(o.get().shape)->holdsMedium)
              throw py::value_error(o.label() +
                                    ".set_medium: expected a sphere or a closed mesh, "
                                    "found a " +
                                    o.get().shape);
            nx::MediumDesc d;
            d.loc = o.get().loc;
            const std::string p = o.label() + ".set_medium: ";
            d.params.set({"sigma_a", spectrumFromPython(sigmaA, p + "sigma_a", d.loc), d.loc});
            d.params.set({"sigma_s", spectrumFromPython(sigmaS, p + "sigma_s", d.loc), d.loc});
            d.params.set({"g", rangedArgument(g, p + "g", nx::kPhaseGRange), d.loc});
            o.get().medium = d;
            o.s->edits.push_back(o.label() + ".set_medium(" +
                                 py::repr(py::make_tuple(sigmaA, sigmaS, g)).cast<std::string>() +
                                 ")");
            return MediumView{o};
          },
          py::arg("sigma_a"), py::arg("sigma_s"), py::arg("g") = 0.0,
          "Fills a sphere or closed mesh with a homogeneous medium (replacing any); returns it")
      .def_property_readonly(
          "shape", [](const ObjectView& o) { return o.get().shape; },
          "Its kind: sphere, plane, triangle, quad, mesh, box, disk or cylinder "
          "(docs/reference/shapes.md)")
      .def_property_readonly(
          "line", [](const ObjectView& o) { return o.get().loc.line; },
          "Its line in the scene file")
      .def_property_readonly("material", &ObjectView::material,
                             "Its material (its own, or the named one it refers to)")
      .def_property_readonly(
          "material_id",
          [](const ObjectView& o) -> py::object {
            return o.get().materialRef.empty() ? py::object(py::none())
                                               : py::object(py::str(o.get().materialRef));
          },
          "The id of the named material it uses, or None")
      .def_property(
          "emission", [](const ObjectView& o) { return spectrumToPythonOpt(o.get().emission); },
          [](const ObjectView& o, const py::object& value) {
            const std::string param = o.label() + ".emission";
            if (value.is_none())
              o.get().emission.reset();
            else
              o.get().emission = spectrumFromPython(value, param, o.get().loc);
            record(*o.s, param, value);
          },
          "Its emitted radiance (an area light; W m^-2 sr^-1 nm^-1): a number, an illuminant "
          "name or (wavelengths_nm, values); None: not a light");
  return object;
}

// An object's mesh arrays and its shape kinds' parameters.
void bindObjectShape(py::class_<ObjectView>& object) {
  object
      .def_property(
          "vertices",
          [](const ObjectView& o) -> py::object {
            const nx::ParameterSet& g = o.get().geometry;
            const auto names = cornerNames(o.get().shape);
            if (!names) { // a mesh's rows (the shape parameter), or None
              const nx::Parameter* q = g.find("vertices");
              return q ? parameterToPython(q->value) : py::object(py::none());
            }
            py::list out;
            for (const char* n : *names) out.append(tupleOf(*g.get<nx::Vec3d>(n)));
            return py::tuple(out);
          },
          [](const ObjectView& o, const py::object& value) {
            const std::string param = o.label() + ".vertices";
            const auto names = cornerNames(o.get().shape);
            if (!names) { // a mesh's rows, checked as every shape parameter
              setShapeParameters(o, {{"vertices", value}});
              record(*o.s, param, value);
              return;
            }
            if (!(py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) ||
                py::len(value) != 3)
              throw py::type_error(param + ": expected three points");
            // All three at once: the kind checks them together.
            const nx::ParameterSet before = o.get().geometry;
            try {
              for (int i = 0; i < 3; ++i)
                o.get().geometry.set(
                    {(*names)[i],
                     pointArgument(value[py::int_(i)], param + "[" + std::to_string(i) + "]"),
                     before.locOf((*names)[i], o.get().loc)});
              if (const auto problem =
                      nx::shapeProblem(*nx::findShapeKind(o.get().shape), o.get().geometry))
                throw py::value_error(param + ": expected " + problem->expected + ", found " +
                                      problem->found);
            } catch (...) {
              o.get().geometry = before;
              throw;
            }
            record(*o.s, param, value);
          },
          "A triangle's (vA, vB, vC) or a quad's (origin, edge_u, edge_v) together; a mesh's "
          "vertex rows ((N, 3) array)")
      .def_property_readonly(
          "name",
          [](const ObjectView& o) -> py::object {
            return o.get().name.empty() ? py::object(py::none())
                                        : py::object(py::str(o.get().name));
          },
          "Its name=\"...\" in the scene file (names its region in comparisons), or None")
      .def_property(
          "emission_scale", [](const ObjectView& o) { return o.get().emissionScale; },
          [](const ObjectView& o, const py::object& value) {
            if (!o.get().emission)
              throw py::value_error(o.label() + ".emission_scale: the object emits no light");
            o.get().emissionScale =
                rangedArgument(value, o.label() + ".emission_scale", nx::kEmissionScaleRange);
            record(*o.s, o.label() + ".emission_scale", value);
          },
          "The factor on its emission (> 0)")
      .def_property(
          "emission_at",
          [](const ObjectView& o) -> py::object {
            const auto& a = o.get().emissionAt;
            return a ? py::object(py::float_(*a)) : py::object(py::none());
          },
          [](const ObjectView& o, const py::object& value) {
            const std::string param = o.label() + ".emission_at";
            if (!o.get().emission) throw py::value_error(param + ": the object emits no light");
            if (value.is_none())
              o.get().emissionAt.reset();
            else {
              o.get().emissionAt = rangedArgument(value, param, nx::kMeasuredDistanceRange);
              o.get().emissionFlux = false;
            }
            record(*o.s, param, value);
          },
          "Its emission is the irradiance on its axis at this distance (None: radiance)")
      .def_property(
          "emission_quantity",
          [](const ObjectView& o) {
            return o.get().emissionAt ? "irradiance" : o.get().emissionFlux ? "flux" : "radiance";
          },
          [](const ObjectView& o, const py::object& given) {
            const std::string param = o.label() + ".emission_quantity";
            const std::string value = stringArgument(given, param.c_str());
            if (!o.get().emission) throw py::value_error(param + ": the object emits no light");
            if (value == "irradiance" && !o.get().emissionAt)
              throw py::value_error(param + ": 'irradiance' needs a distance: set emission_at");
            if (value != "radiance" && value != "flux" && value != "irradiance")
              throw py::value_error(
                  param + ": expected 'radiance', 'flux' or 'irradiance', found '" + value + "'");
            if (value != "irradiance") o.get().emissionAt.reset();
            o.get().emissionFlux = value == "flux";
            record(*o.s, param, py::str(value));
          },
          "What its emission gives: 'radiance', 'flux' (total) or 'irradiance' (emission_at)")
      .def("__repr__", [](const ObjectView& o) {
        return "<nxrender.Object " + o.label() + " " + o.get().shape + " (line " +
               std::to_string(o.get().loc.line) + ")>";
      });
  // One property per parameter any shape kind declares (the first declaration of a name): None
  // on an object whose kind does not take it; setting it there is refused.
  std::vector<std::string> shapeNames;
  for (const nx::ShapeKindSpec& kind : nx::shapeKinds())
    for (const nx::ShapeParameter& sp : kind.params()) {
      // (a mesh's vertices share the triangles' and quads' `vertices` property above)
      if (std::string(sp.spec.name) == "vertices" ||
          std::find(shapeNames.begin(), shapeNames.end(), sp.spec.name) != shapeNames.end())
        continue;
      shapeNames.push_back(sp.spec.name);
      const std::string name = sp.spec.name;
      object.def_property(
          sp.spec.name,
          [name](const ObjectView& o) -> py::object {
            const nx::Parameter* q = o.get().geometry.find(name);
            return q ? parameterToPython(q->value) : py::object(py::none());
          },
          [name](const ObjectView& o, const py::object& value) {
            setShapeParameters(o, {{name, value}});
            record(*o.s, o.label() + "." + name, value);
          },
          sp.spec.doc);
    }
}

// nxrender.Light and nxrender.NamedSpectrum.
void bindLightClasses(py::module_& m) {
  py::class_<LightView> light(m, "Light",
                              "A <light>: a point or spot light; a property per parameter of "
                              "its kind (docs/reference/lights.md)");
  light.def_property_readonly(
      "kind", [](const LightView& l) { return l.get().kind; }, "point, spot, ...");
  bindTakenParameters(light, nx::lightKinds(), nx::ParamType::Dye);

  py::class_<NamedSpectrumView>(m, "NamedSpectrum",
                                "A <spectrum name=...> of the scene, used by its name")
      .def_property_readonly("name", [](const NamedSpectrumView& v) { return v.get().name; })
      .def_property(
          "value", [](const NamedSpectrumView& v) { return spectrumToPython(v.get().spectrum); },
          [](const NamedSpectrumView& v, const py::object& value) {
            const std::string param = v.label() + ".value";
            nx::SpectrumDesc d = spectrumFromPython(value, param, v.get().loc);
            if (d.kind == nx::SpectrumDesc::Kind::Texture)
              throw py::value_error(param + ": expected a spectrum, found a texture");
            if (d.kind == nx::SpectrumDesc::Kind::Name)
              throw py::value_error(param + ": expected numbers or a CSV file (a named spectrum "
                                            "is defined by values, not by another name)");
            v.get().spectrum = d;
            record(*v.s, param, value);
          },
          "Its values: a number, (wavelengths_nm, values) or \"csv:FILE[#COLUMN]\"")
      .def("__repr__",
           [](const NamedSpectrumView& v) { return "<nxrender.NamedSpectrum " + v.label() + ">"; });
}

// nxrender.Camera.
void bindCameraClass(py::module_& m) {
  py::class_<CameraView>(m, "Camera", "The scene's camera")
      .def_property(
          "position", [](const CameraView& c) { return tupleOf(c.s->desc.camera.position); },
          [](const CameraView& c, const py::object& value) {
            if (c.s->desc.camera.extrinsics)
              throw py::value_error("camera.position: the camera is placed by <extrinsics>");
            const nx::Vec3d p = pointArgument(value, "camera.position");
            editCamera(*c.s, "camera.position", value, [&](nx::CameraDesc& d) { d.position = p; });
          })
      .def_property(
          "look_at", [](const CameraView& c) { return tupleOf(c.s->desc.camera.lookAt); },
          [](const CameraView& c, const py::object& value) {
            if (c.s->desc.camera.extrinsics)
              throw py::value_error("camera.look_at: the camera is placed by <extrinsics>");
            const nx::Vec3d p = pointArgument(value, "camera.look_at");
            editCamera(*c.s, "camera.look_at", value, [&](nx::CameraDesc& d) { d.lookAt = p; });
          })
      .def_property(
          "up", [](const CameraView& c) { return tupleOf(c.s->desc.camera.up); },
          [](const CameraView& c, const py::object& value) {
            const nx::Vec3d u = pointArgument(value, "camera.up");
            editCamera(*c.s, "camera.up", value, [&](nx::CameraDesc& d) { d.up = u; });
          })
      .def_property(
          "fov",
          [](const CameraView& c) -> py::object {
            return c.s->desc.camera.intrinsics
                       ? py::object(py::none())
                       : py::object(py::float_(c.s->desc.camera.fovDegrees));
          },
          [](const CameraView& c, const py::object& value) {
            const double fov = rangedArgument(value, "camera.fov", nx::kFovRange);
            editCamera(*c.s, "camera.fov", value, [&](nx::CameraDesc& d) {
              d.fovDegrees = fov;
              d.intrinsics.reset();
            });
          },
          "Horizontal field of view in degrees (None when intrinsics are given; setting it "
          "removes them)")
      .def_property(
          "intrinsics",
          [](const CameraView& c) -> py::object {
            const auto& k = c.s->desc.camera.intrinsics;
            return k ? py::object(py::make_tuple((*k)[0], (*k)[1], (*k)[2], (*k)[3]))
                     : py::object(py::none());
          },
          [](const CameraView& c, const py::object& value) {
            const std::vector<double> v = numbersArgument(value, "camera.intrinsics", 4);
            editCamera(*c.s, "camera.intrinsics", value, [&](nx::CameraDesc& d) {
              d.intrinsics = std::array<double, 4>{v[0], v[1], v[2], v[3]};
            });
          },
          "OpenCV intrinsics (fx, fy, cx, cy) in pixels, or None")
      .def_property(
          "distortion",
          [](const CameraView& c) {
            const auto& d = c.s->desc.camera.distortion;
            return py::make_tuple(d[0], d[1], d[2], d[3], d[4]);
          },
          [](const CameraView& c, const py::object& value) {
            const std::vector<double> v = numberListArgument(value, "camera.distortion", 4);
            if (v.size() > 5)
              throw py::value_error("camera.distortion: expected k1, k2, p1, p2[, k3]");
            for (double x : v)
              if (!(std::abs(x) <= 1e4))
                throw py::value_error(
                    "camera.distortion: expected coefficients within [-1e4, 1e4]");
            editCamera(*c.s, "camera.distortion", value, [&](nx::CameraDesc& d) {
              d.distortion = {};
              std::copy(v.begin(), v.end(), d.distortion.begin());
              d.distortionLoc = d.loc;
            });
          },
          "OpenCV distortion (k1, k2, p1, p2, k3); a fold in the image is refused at render")
      .def_property(
          "thin_lens",
          [](const CameraView& c) -> py::object {
            const auto& l = c.s->desc.camera.thinLens;
            return l ? py::object(py::make_tuple((*l)[0], (*l)[1])) : py::object(py::none());
          },
          [](const CameraView& c, const py::object& value) {
            if (value.is_none())
              return editCamera(*c.s, "camera.thin_lens", value,
                                [](nx::CameraDesc& d) { d.thinLens.reset(); });
            const std::vector<double> v = numbersArgument(value, "camera.thin_lens", 2);
            editCamera(*c.s, "camera.thin_lens", value, [&](nx::CameraDesc& d) {
              d.thinLens = std::array<double, 2>{v[0], v[1]};
            });
          },
          "(aperture radius, focus distance) in scene units, or None (a pinhole)")
      .def_property(
          "extrinsics",
          [](const CameraView& c) -> py::object {
            const auto& e = c.s->desc.camera.extrinsics;
            if (!e) return py::none();
            return py::cast(std::vector<double>(e->begin(), e->end()));
          },
          [](const CameraView& c, const py::object& value) {
            if (value.is_none())
              throw py::value_error("camera.extrinsics: expected 12 numbers (r11 .. r33, t1, t2, "
                                    "t3); a camera placed by extrinsics has no look-at form");
            const std::vector<double> v = numbersArgument(value, "camera.extrinsics", 12);
            editCamera(*c.s, "camera.extrinsics", value, [&](nx::CameraDesc& d) {
              d.extrinsics = std::array<double, 12>{};
              std::copy(v.begin(), v.end(), d.extrinsics->begin());
            });
          },
          "OpenCV extrinsics r11 .. r33, t1, t2, t3 (x_cam = R x_world + t), or None");
}

// nxrender.Scene: construction, data and lists (bindSceneSettings: the settings).
py::class_<PyScene> bindSceneClass(py::module_& m) {
  bindSceneLists(m);
  py::class_<PyScene> scene(m, "Scene",
                            "A scene file read once and edited from Python; render it with "
                            "nxrender.render(scene). Edits are checked like the file's values and "
                            "recorded in the image's nxrender.sceneEdits attribute.");
  scene
      .def(py::init([](const py::object& path) {
             PyScene s;
             s.state = std::make_shared<SceneState>();
             if (path.is_none()) {
               s.state->desc = nx::parseSceneTree(emptySceneTree(), "<empty>");
               return s;
             }
             const std::string p = pathArgument(path, "path");
             py::gil_scoped_release release;
             s.state->desc = nx::loadScene(p);
             return s;
           }),
           py::arg("path") = py::none(),
           "Reads a scene file (errors: nxrender.Error with file:line); without a path, an "
           "empty scene (no objects or lights; 64 x 64 pixels, spectral_mcpt, 16 spp; the "
           "camera at (0, 0, -5) looking at the origin)")
      .def_static(
          "from_dict",
          [](const py::object& d, const std::string& name) {
            const nx::SceneTree tree = treeFromPython(d, "");
            PyScene s;
            s.state = std::make_shared<SceneState>();
            s.state->desc = nx::parseSceneTree(tree, name);
            return s;
          },
          py::arg("d"), py::arg("name") = "<dict>",
          "A scene from a dict keyed by the scene format's element and parameter names "
          "(docs/python.md, 'Scenes from data'); errors name the path in the dict "
          "('objects[2].radius: ...'). Relative file names are relative to `name`'s directory "
          "(the working directory by default).")
      .def_static(
          "from_text",
          [](const std::string& text, const std::string& name) {
            PyScene s;
            s.state = std::make_shared<SceneState>(loadState(text, name));
            return s;
          },
          py::arg("text"), py::arg("name") = "<string>",
          "A scene from its XML text; `name` names it in errors and anchors relative paths "
          "(its directory)")
      .def(
          "to_dict", [](const PyScene& s) { return treeToPython(nx::sceneToTree(s.state->desc)); },
          "The scene as a dict of the scene format's names (Scene.from_dict reads it back to the "
          "same scene); file names as the scene holds them (relative to the working directory "
          "or absolute)")
      .def(
          "to_text",
          [](const PyScene& s, const py::object& path) {
            const std::string base =
                path.is_none()
                    ? std::string()
                    : std::filesystem::path(pathArgument(path, "path")).parent_path().string();
            return nx::sceneToText(s.state->desc, base.empty() && !path.is_none() ? "." : base);
          },
          py::arg("path") = py::none(),
          "The scene as scene text that reads back to the same scene (Scene.from_text(text, "
          "path)); with `path`, file names are written relative to its directory, so the text "
          "can be saved there")
      .def_property_readonly("file", [](const PyScene& s) { return s.state->desc.file; })
      .def_property_readonly("warnings", [](const PyScene& s) { return s.state->desc.warnings; })
      .def_property_readonly(
          "edits", [](const PyScene& s) { return s.state->edits; },
          "The edits made so far, in order")
      .def_property(
          "resolution",
          [](const PyScene& s) {
            return py::make_tuple(s.state->desc.settings.width, s.state->desc.settings.height);
          },
          [](const PyScene& s, const py::object& value) {
            const auto v = integersArgument(value, "resolution", 2);
            for (long long x : v)
              if (x < 1 || x > nx::kMaxResolution)
                throw py::value_error("resolution: expected sizes in [1, 65536], found " +
                                      std::to_string(x));
            s.state->desc.settings.width = static_cast<int>(v[0]);
            s.state->desc.settings.height = static_cast<int>(v[1]);
            record(*s.state, "resolution", value);
          },
          "(width, height) in pixels");
  return scene;
}

// The scene's settings as properties, and copies.
void bindSceneSettings(py::class_<PyScene>& scene) {
  scene
      .def_property(
          "spp", [](const PyScene& s) { return s.state->desc.settings.samples; },
          [](const PyScene& s, const py::object& value) {
            s.state->desc.settings.samples =
                static_cast<int>(integerArgument(value, "spp", 1, 1 << 30));
            record(*s.state, "spp", value);
          },
          "Samples per pixel (<sampl>)")
      .def_property(
          "seed", [](const PyScene& s) { return s.state->desc.settings.seed; },
          [](const PyScene& s, const py::object& value) {
            s.state->desc.settings.seed =
                static_cast<uint32_t>(integerArgument(value, "seed", 0, 2147483647));
            record(*s.state, "seed", value);
          })
      .def_property(
          "depth", [](const PyScene& s) { return s.state->desc.settings.depth; },
          [](const PyScene& s, const py::object& value) {
            s.state->desc.settings.depth =
                static_cast<int>(integerArgument(value, "depth", 0, 100000));
            record(*s.state, "depth", value);
          },
          "Bounce count")
      .def_property(
          "bands", [](const PyScene& s) { return s.state->desc.settings.bands.toString(); },
          [](const PyScene& s, const py::object& value) {
            s.state->desc.settings.bands =
                nx::Sensor::parse(stringArgument(value, "bands"), "bands");
            s.state->desc.settings.sensorFile.clear(); // no longer the file's sensor
            s.state->desc.settings.sensorCentres.clear();
            record(*s.state, "bands", value);
          },
          "The output bands ('400:700:10', 'gaussian:...', 'boxes:...')")
      .def_property(
          "background",
          [](const PyScene& s) { return spectrumToPythonOpt(s.state->desc.settings.background); },
          [](const PyScene& s, const py::object& value) {
            if (value.is_none())
              s.state->desc.settings.background.reset();
            else
              s.state->desc.settings.background =
                  spectrumFromPython(value, "background", s.state->desc.settings.loc);
            record(*s.state, "background", value);
          },
          "Uniform environment radiance (a spectrum), or None (black)")
      .def_property(
          "illuminant",
          [](const PyScene& s) { return spectrumToPythonOpt(s.state->desc.settings.illuminant); },
          [](const PyScene& s, const py::object& value) {
            if (value.is_none())
              s.state->desc.settings.illuminant.reset();
            else
              s.state->desc.settings.illuminant =
                  spectrumFromPython(value, "illuminant", s.state->desc.settings.loc);
            record(*s.state, "illuminant", value);
          },
          "The preview's white (<illum>, a spectrum), or None (D65)")
      .def_property(
          "mode", [](const PyScene& s) { return nx::renderModeName(s.state->desc.settings.mode); },
          [](const PyScene& s, const py::object& value) {
            const auto mode = nx::parseRenderMode(stringArgument(value, "mode"));
            if (!mode)
              throw py::value_error("mode: expected rt, mcpt or spectral_mcpt, found " +
                                    py::repr(value).cast<std::string>());
            s.state->desc.settings.mode = *mode;
            record(*s.state, "mode", value);
          },
          "The rendering mode (<mode>): rt, mcpt or spectral_mcpt")
      .def_property(
          "path", [](const PyScene& s) { return s.state->desc.settings.outputPath; },
          [](const PyScene& s, const py::object& value) {
            s.state->desc.settings.outputPath = stringArgument(value, "path");
            record(*s.state, "path", value);
          },
          "The output the command line writes (<path>; renders from Python return images)")
      .def_property_readonly(
          "spectra",
          [](const PyScene& s) {
            py::dict d;
            for (size_t i = 0; i < s.state->desc.spectra.size(); ++i)
              d[py::str(s.state->desc.spectra[i].name)] = NamedSpectrumView{s.state, i};
            return ReadOnlyMapping{d, "scene.spectra"};
          },
          "The named spectra (<spectrum name=...>) by name")
      .def_property_readonly("camera", [](const PyScene& s) { return CameraView{s.state}; })
      .def_property_readonly(
          "objects", [](const PyScene& s) { return objectList(s.state); },
          "The objects in file order: a live list (append, insert, del, pop, item assignment "
          "of an Object or a dict)")
      .def_property_readonly(
          "lights", [](const PyScene& s) { return lightList(s.state); },
          "The <light> elements in file order: a live list as objects")
      .def_property_readonly(
          "materials",
          [](const PyScene& s) {
            py::dict d;
            for (size_t i = 0; i < s.state->desc.materials.size(); ++i)
              d[py::str(s.state->desc.materials[i].id)] = MaterialView{s.state, true, i};
            return ReadOnlyMapping{d, "scene.materials"};
          },
          "The named materials (<material id=...>) by id")
      .def(
          "copy",
          [](const PyScene& s) {
            PyScene c;
            c.state = std::make_shared<SceneState>(*s.state);
            return c;
          },
          "An independent copy (edits to one do not change the other)")
      .def("__repr__", [](const PyScene& s) {
        return "<nxrender.Scene " + s.state->desc.file + ": " +
               std::to_string(s.state->desc.objects.size()) + " objects, " +
               std::to_string(s.state->edits.size()) + " edits>";
      });
}

} // namespace

void bindScene(py::module_& m) {
  bindFluorescenceClass(m);
  bindMaterialClass(m);
  bindMediumClasses(m);
  py::class_<ObjectView> object = bindObjectClass(m);
  bindObjectShape(object);
  bindLightClasses(m);
  bindCameraClass(m);
  py::class_<PyScene> scene = bindSceneClass(m);
  bindSceneSettings(scene);
}

} // namespace nxpy
