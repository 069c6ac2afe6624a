// Scene.parameters(), Scene.get(name), Scene.set(name, value): every parameter of the scene
// by a stable name (the names Scene.edits records), with its type, unit, range and meaning.
// Shape, material and light parameters come from the kinds' schemas (accel/shape_kinds.h,
// integrators/materials/material_kind.h, integrators/lights/light_kinds.h); the others from
// the table of core/params/scene_parameters.cpp. Values are read and set through the views'
// properties, so a value set by name is checked and recorded exactly as one set by attribute.

#include "apps/python/py_scene_parameters.h"

#include <pybind11/stl.h>

#include <cctype>

#include "accel/shape_kinds.h"
#include "core/params/material_parameters.h"
#include "core/params/scene_parameters.h"
#include "integrators/lights/light_kinds.h"
#include "integrators/materials/material_kind.h"
#include "integrators/media/medium_kinds.h"

namespace nxpy {
namespace {

const nx::FixedParameter& fixed(const std::string& key) {
  return nx::fixedParameter(key);
}

// One entry of parameters(): the name and its description.
struct Entry {
  std::string name, type, unit, doc, defaultText;
  const nx::ParameterRange* range = nullptr;
  bool differentiable = false;
};

void addFixed(std::vector<Entry>& out, const std::string& name, const std::string& key) {
  const nx::FixedParameter& f = fixed(key);
  out.push_back({name, f.type, f.unit, f.doc, "", f.range, f.differentiable});
}

// The fluorescence fields of a material or a dye named `prefix`.
void addFluorescence(std::vector<Entry>& out, const std::string& prefix,
                     const nx::FluorescenceDesc& f, bool dye) {
  if (f.matrixCsv || f.matrix) return addFixed(out, prefix + ".matrix", "fluorescence.matrix");
  if (f.eem) { // an imported EEM: the yield and peak it was made absolute with
    if (f.eem->referenceFile.empty())
      addFixed(out, prefix + ".quantum_yield", "fluorescence.quantum_yield");
    if (!f.eem->absorptance)
      addFixed(out, prefix + ".peak_absorptance", "fluorescence.peak_absorptance");
    addFixed(out, prefix + ".concentration", "fluorescence.concentration");
    return;
  }
  for (const char* field :
       {"absorption_nm", "stokes_nm", "width_nm", "skew", "quantum_yield", "peak_absorptance"})
    if (!(dye && std::string(field) == "peak_absorptance"))
      addFixed(out, prefix + "." + field, std::string("fluorescence.") + field);
  if (!dye) addFixed(out, prefix + ".concentration", "fluorescence.concentration");
}

// Every parameter a material's kind takes (given or not), named `label.<parameter>`.
void addMaterial(std::vector<Entry>& out, const std::string& label, const nx::MaterialDesc& m) {
  const nx::MaterialKindSpec* kind = nx::findMaterialKind(m.material);
  if (!kind) return;
  for (const nx::KindParameter& p : kind->params) {
    const nx::ParamSpec& spec = *nx::materialParameter(p.name);
    out.push_back({label + "." + p.name, nx::paramTypeName(spec.type), spec.unit,
                   *p.doc ? p.doc : spec.doc, p.defaultText, spec.range, spec.differentiable});
    if (spec.type == nx::ParamType::Fluorescence)
      if (const auto* f = m.params.get<nx::FluorescenceDesc>("fluorescence"))
        addFluorescence(out, label + ".fluorescence", *f, false);
  }
}

// Every parameter a light's or medium's kind takes, named `label.<parameter>` (a dye is listed
// by its fields).
void addTaken(std::vector<Entry>& out, const std::string& label,
              std::span<const nx::TakenParameter> params) {
  for (const nx::TakenParameter& p : params)
    if (p.spec.type != nx::ParamType::Dye)
      out.push_back({label + "." + p.spec.name, nx::paramTypeName(p.spec.type), p.spec.unit,
                     p.spec.doc, p.defaultText, p.spec.range, p.spec.differentiable});
}

std::vector<Entry> entries(const SceneState& s) {
  std::vector<Entry> out;
  for (const char* k :
       {"resolution", "mode", "spp", "seed", "depth", "bands", "background", "illuminant", "path"})
    addFixed(out, k, k);
  for (const nx::NamedSpectrumDesc& n : s.desc.spectra)
    addFixed(out, "spectra['" + n.name + "'].value", "spectrum.value");
  const nx::CameraDesc& c = s.desc.camera;
  if (!c.extrinsics)
    for (const char* k : {"position", "look_at", "up"})
      addFixed(out, std::string("camera.") + k, std::string("camera.") + k);
  else
    addFixed(out, "camera.extrinsics", "camera.extrinsics");
  addFixed(out, c.intrinsics ? "camera.intrinsics" : "camera.fov",
           c.intrinsics ? "camera.intrinsics" : "camera.fov");
  addFixed(out, "camera.distortion", "camera.distortion");
  addFixed(out, "camera.thin_lens", "camera.thin_lens");
  for (size_t i = 0; i < s.desc.objects.size(); ++i) {
    const nx::ObjectDesc& o = s.desc.objects[i];
    const std::string label = "objects[" + std::to_string(i) + "]";
    if (const nx::ShapeKindSpec* kind = nx::findShapeKind(o.shape))
      for (const nx::ShapeParameter& p : kind->params())
        out.push_back({label + "." + p.spec.name, nx::paramTypeName(p.spec.type), p.spec.unit,
                       p.spec.doc, "", p.spec.range, p.spec.differentiable});
    addFixed(out, label + ".emission", "object.emission");
    if (o.emission)
      for (const char* f : {"emission_scale", "emission_at", "emission_quantity"})
        addFixed(out, label + "." + f, std::string("object.") + f);
    if (o.materialRef.empty()) addMaterial(out, label, o);
    if (o.medium) {
      if (const nx::MediumKindSpec* kind = nx::findMediumKind(o.medium->kind))
        addTaken(out, label + ".medium", kind->params());
      if (const auto* dye = o.medium->params.get<nx::FluorescenceDesc>("fluorescence")) {
        addFixed(out, label + ".medium.dye_peak", "medium.dye_peak");
        addFluorescence(out, label + ".medium.dye", *dye, true);
      }
    }
  }
  for (const nx::NamedMaterialDesc& m : s.desc.materials)
    addMaterial(out, "materials['" + m.id + "']", m.material);
  for (size_t i = 0; i < s.desc.lights.size(); ++i) {
    const std::string label = "lights[" + std::to_string(i) + "]";
    if (const nx::LightKindSpec* kind = nx::findLightKind(s.desc.lights[i].kind))
      addTaken(out, label, kind->params());
  }
  return out;
}

// A name split into its steps: "objects[1].fluorescence.stokes_nm" -> (objects, 1),
// (fluorescence), (stokes_nm); "materials['card'].reflectance" -> (materials, 'card'), ...
struct Step {
  std::string attribute;
  py::object index; ///< None, an int or a str
};

std::vector<Step> steps(const std::string& name) {
  std::vector<Step> out;
  size_t i = 0;
  auto bad = [&] { return py::key_error("no scene parameter named '" + name + "'"); };
  while (i < name.size()) {
    Step s;
    s.index = py::none();
    while (i < name.size() && (std::isalnum(static_cast<unsigned char>(name[i])) || name[i] == '_'))
      s.attribute += name[i++];
    if (s.attribute.empty()) throw bad();
    if (i < name.size() && name[i] == '[') {
      const size_t close = name.find(']', i);
      if (close == std::string::npos) throw bad();
      const std::string inside = name.substr(i + 1, close - i - 1);
      if (inside.size() >= 2 && (inside.front() == '\'' || inside.front() == '"') &&
          inside.back() == inside.front())
        s.index = py::str(inside.substr(1, inside.size() - 2));
      else if (!inside.empty() && inside.find_first_not_of("0123456789") == std::string::npos)
        s.index = py::int_(std::stoll(inside));
      else
        throw bad();
      i = close + 1;
    }
    out.push_back(std::move(s));
    if (i < name.size()) {
      if (name[i] != '.') throw bad();
      ++i;
      if (i == name.size()) throw bad();
    }
  }
  if (out.empty() || !out.back().index.is_none()) throw bad();
  return out;
}

// The canonical spelling of a name (materials["x"] -> materials['x']), checked to be one of
// the scene's parameters.
std::string knownName(const SceneState& s, const std::string& name) {
  std::string canonical = name;
  for (char& ch : canonical)
    if (ch == '"') ch = '\'';
  for (const Entry& e : entries(s))
    if (e.name == canonical) return canonical;
  throw py::key_error("no scene parameter named '" + name + "' (Scene.parameters() lists them)");
}

// An object's material parameters are named after the object ("objects[1].reflectance", as
// errors and edits name them): the step goes through its material view.
py::object owner(const py::object& at, const std::string& attribute) {
  if (!py::hasattr(at, attribute.c_str()) && py::hasattr(at, "material"))
    return at.attr("material");
  return at;
}

// The object holding the last step, walking the views from the scene.
py::object holder(const py::object& scene, const std::vector<Step>& path) {
  py::object at = scene;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const py::object from = owner(at, path[i].attribute);
    at = from.attr(path[i].attribute.c_str());
    if (!path[i].index.is_none()) at = at[path[i].index];
    if (at.is_none())
      throw py::key_error("the scene has no " + path[i].attribute + " here any more");
  }
  return owner(at, path.back().attribute);
}

} // namespace

void bindSceneParameters(py::module_& m) {
  py::object scene = m.attr("Scene");
  scene.attr("parameters") = py::cpp_function(
      [](const py::object& self) {
        const PyScene& s = self.cast<const PyScene&>();
        py::dict out;
        for (const Entry& e : entries(*s.state)) {
          py::dict d;
          const std::vector<Step> path = steps(e.name);
          const py::object at = holder(self, path);
          py::object value = at.attr(path.back().attribute.c_str());
          // A fluorescence is a view of its fields (listed as parameters of their own).
          if (e.type == nx::paramTypeName(nx::ParamType::Fluorescence) && !value.is_none())
            value = value.attr("matrix_file").is_none() && value.attr("matrix").is_none()
                        ? py::str("model")
                        : py::str("matrix");
          d["value"] = value;
          d["type"] = e.type;
          d["unit"] = e.unit;
          d["range"] = e.range ? py::object(py::make_tuple(e.range->lo, e.range->hi))
                               : py::object(py::none());
          d["default"] = e.defaultText.empty() ? py::object(py::none()) : py::str(e.defaultText);
          d["doc"] = e.doc;
          d["differentiable"] = e.differentiable;
          out[py::str(e.name)] = d;
        }
        return out;
      },
      py::name("parameters"), py::is_method(scene),
      "Every parameter of the scene by its stable name (the names Scene.edits records): a dict "
      "name -> {value, type, unit, range, default, doc, differentiable}. Material parameters a "
      "kind takes are "
      "listed whether given or not (value None: the kind's default).");
  scene.attr("get") = py::cpp_function(
      [](const py::object& self, const std::string& name) -> py::object {
        const PyScene& s = self.cast<const PyScene&>();
        const std::vector<Step> path = steps(knownName(*s.state, name));
        const py::object at = holder(self, path);
        return at.attr(path.back().attribute.c_str());
      },
      py::name("get"), py::is_method(scene), py::arg("name"),
      "The value of the parameter called `name` (see parameters())");
  scene.attr("set") = py::cpp_function(
      [](const py::object& self, const std::string& name, const py::object& value) {
        const PyScene& s = self.cast<const PyScene&>();
        const std::vector<Step> path = steps(knownName(*s.state, name));
        py::setattr(holder(self, path), path.back().attribute.c_str(), value);
      },
      py::name("set"), py::is_method(scene), py::arg("name"), py::arg("value"),
      "Sets the parameter called `name`, checked and recorded as the attribute's setter does "
      "(ValueError / TypeError naming it)");
}

} // namespace nxpy
