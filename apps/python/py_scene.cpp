// nxrender.Scene and its views (camera, objects, materials, fluorescence, lights).

#include "apps/python/py_scene.h"
#include "apps/python/py_scene_fields.h"
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

void record(SceneState& s, const std::string& what, const py::handle& value) {
  s.record(what, py::repr(value).cast<std::string>());
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
  (void)v.editable();
  if (value.is_none()) {
    v.editable().params.erase(spec.name);
    return;
  }
  requireKindTakes(v, spec.name, param);
  // Converted before any reference into the scene is taken (the conversion may run Python
  // code that edits the scene's lists).
  nx::ParamValue converted = parameterFromPython(spec, value, param, v.loc());
  nx::MaterialDesc& d = v.editable();
  d.params.set({spec.name, std::move(converted), v.loc()});
  nx::forEachWord(spec.excludes, [&](const std::string& x) { d.params.erase(x); });
}

// Gives a material a measured matrix from Python arrays (replacing any fluorescence), checked
// as a CSV matrix is; the edit is recorded with a digest of the content (a numpy repr elides).
void setMeasuredMatrix(const MaterialView& v, const py::handle& value, const std::string& param) {
  (void)v.editable();
  requireKindTakes(v, "fluorescence", param);
  const std::shared_ptr<const nx::MeasuredMatrix> m = matrixFromPython(value, param);
  try {
    nx::checkMeasuredMatrix(*m, param);
  } catch (const nx::Error& e) {
    throw py::value_error(e.what());
  }
  nx::FluorescenceDesc f;
  f.loc = v.loc();
  f.matrix = m;
  f.matrixDigest = nx::measuredMatrixDigest(*m);
  v.editable().params.set({"fluorescence", f, v.loc()});
  v.s->edits.push_back(param + " = " + matrixEditText(*m));
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
            if (value.is_none()) {
              if (decl->required) throw py::value_error(param + ": " + v.kindText() + " needs it");
              v.params().erase(name);
            } else {
              // Converted before the reference is taken (conversions may edit the scene).
              nx::ParamValue converted = parameterFromPython(decl->spec, value, param, v.loc());
              nx::ParameterSet& p = v.params();
              p.set({name, std::move(converted), p.locOf(name, v.loc())});
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
  // The new geometry is made from copies; the object is looked up again only after every
  // value is converted (a conversion may run Python code that edits the scene's lists).
  const nx::ShapeKindSpec& kind = *nx::findShapeKind(o.get().shape);
  const nx::SourceLocation loc = o.get().loc;
  const nx::ParameterSet before = o.get().geometry;
  nx::ParameterSet next = before;
  for (const auto& [name, value] : values) {
    const std::string param = o.label() + "." + name;
    const nx::ShapeParameter& decl = shapeParameterOf(kind, name, param);
    if (value.is_none()) {
      next.erase(name);
      continue;
    }
    next.set({name, parameterFromPython(decl.spec, value, param, loc), before.locOf(name, loc)});
    nx::forEachWord(decl.spec.excludes, [&](const std::string& x) { next.erase(x); });
  }
  nx::ObjectDesc& d = o.get();
  if (d.shape != kind.name)
    throw py::value_error(o.label() + ": was replaced by a " + d.shape +
                          " while its values were converted");
  if (const auto problem = nx::shapeProblem(kind, next))
    throw py::value_error(o.label() + "." +
                          (values.size() == 1 ? values[0].first : std::string("update")) +
                          ": expected " + problem->expected + ", found " + problem->found);
  d.geometry = std::move(next);
}

// The model's fields both a material's fluorescence and a dye have: the absorption's colour
// name (read only) and the declared fields (core/params/scene_parameters.h), except those in
// `except`.
template <typename View>
void bindFluorescenceModel(py::class_<View>& c, std::initializer_list<const char*> except = {}) {
  c.def_property_readonly(
      "absorption",
      [](const View& f) -> py::object {
        const auto& d = f.get();
        return d.absorptionName ? py::object(py::str(*d.absorptionName)) : py::object(py::none());
      },
      "Absorption colour name, if the scene gave one");
  bindSceneFields(c, "fluorescence", except);
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

namespace {

// nxrender.Fluorescence.
void bindFluorescenceClass(py::module_& m) {
  py::class_<FluorescenceView> fl(m, "Fluorescence",
                                  "The fluorescence of a material (the re-radiation matrix's "
                                  "parameters; docs/fluorescence.md)");
  bindFluorescenceModel(fl);
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
            (void)v.editable();
            const std::string p = v.label() + ".set_fluorescence: ";
            requireKindTakes(v, "fluorescence", v.label() + ".set_fluorescence");
            nx::FluorescenceDesc f =
                fluorescenceModel(p, v.loc(), absorptionNm, stokesNm, widthNm, skew, quantumYield);
            if (!peakAbsorptance.is_none())
              f.peakAbsorptance =
                  rangedArgument(peakAbsorptance, p + "peak_absorptance", nx::kPeakRange);
            v.editable().params.set({"fluorescence", f, v.loc()}); // after the conversions
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
          "set_fluorescence_spectra",
          [](const MaterialView& v, const py::object& absorptance, const py::object& emission,
             const py::object& quantumYield) {
            (void)v.editable();
            const std::string p = v.label() + ".set_fluorescence_spectra: ";
            requireKindTakes(v, "fluorescence", v.label() + ".set_fluorescence_spectra");
            nx::FluorescenceDesc f;
            f.loc = v.loc();
            auto spectra = std::make_shared<nx::DyeSpectra>();
            spectra->absorptance = spectrumFromPython(absorptance, p + "absorptance", v.loc());
            spectra->emission = spectrumFromPython(emission, p + "emission", v.loc());
            f.spectra = spectra;
            if (!quantumYield.is_none())
              f.quantumYield = rangedArgument(quantumYield, p + "quantum_yield", nx::kYieldRange);
            v.editable().params.set({"fluorescence", f, v.loc()}); // after the conversions
            v.s->record(
                v.label() + ".set_fluorescence_spectra(...)",
                py::repr(py::make_tuple(absorptance, emission, quantumYield)).cast<std::string>());
            return FluorescenceView{v};
          },
          py::arg("absorptance"), py::arg("emission"), py::arg("quantum_yield") = py::none(),
          "Gives the material a dye as a datasheet gives it (replacing any fluorescence): its "
          "absorptance and emission spectra (any spectrum form; emission in photons, any "
          "scale) and its quantum yield (None: 1); returns it")
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
  bindFluorescenceModel(dye, {"peak_absorptance", "matrix", "concentration"});

  py::class_<MediumView> med(m, "Medium",
                             "The participating medium inside a sphere or closed mesh "
                             "(docs/media.md); coefficients per scene unit of length");
  bindTakenParameters(med, nx::mediumKinds(), nx::ParamType::Dye);
  bindSceneFields(med, "medium");
  med.def_property_readonly(
         "kind", [](const MediumView& v) { return v.get().kind; }, "homogeneous")
      .def_property_readonly(
          "dye",
          [](const MediumView& v) -> py::object {
            return v.get().params.has("fluorescence") ? py::cast(DyeView{v})
                                                      : py::object(py::none());
          },
          "The dye dissolved in it (None: none; set_dye(...) adds one)")
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
          "The id of the named material it uses, or None");
  bindSceneFields(object, "object");
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
            // All three converted first (a conversion may run Python code that edits the
            // scene's lists), then set at once: the kind checks them together.
            std::array<nx::Vec3d, 3> points;
            for (int i = 0; i < 3; ++i)
              points[static_cast<size_t>(i)] =
                  pointArgument(value[py::int_(i)], param + "[" + std::to_string(i) + "]");
            const nx::ParameterSet before = o.get().geometry;
            try {
              for (int i = 0; i < 3; ++i)
                o.get().geometry.set({(*names)[i], points[static_cast<size_t>(i)],
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
      .def("__repr__", [](const ObjectView& o) {
        const nx::ObjectDesc& d = o.value(); // (an object no longer in the scene: as it was)
        return "<nxrender.Object " + o.label() + " " + d.shape + " (line " +
               std::to_string(d.loc.line) + ")" +
               (o.item->former ? " no longer in the scene" : "") + ">";
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

  py::class_<NamedSpectrumView> spectrum(m, "NamedSpectrum",
                                         "A <spectrum name=...> of the scene, used by its name");
  spectrum.def_property_readonly("name", [](const NamedSpectrumView& v) { return v.get().name; })
      .def("__repr__",
           [](const NamedSpectrumView& v) { return "<nxrender.NamedSpectrum " + v.label() + ">"; });
  bindSceneFields(spectrum, "spectrum");
}

// nxrender.Camera.
void bindCameraClass(py::module_& m) {
  py::class_<CameraView> camera(m, "Camera", "The scene's camera");
  bindSceneFields(camera, "camera");
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
          "The edits made so far, in order");
  return scene;
}

// The scene's settings as properties, and copies.
void bindSceneSettings(py::class_<PyScene>& scene) {
  bindSceneFields(scene, "");
  scene
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
              d[py::str(s.state->desc.materials[i].id)] = MaterialView{s.state, true, i, nullptr};
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
