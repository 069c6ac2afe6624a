#include "integrators/scene_params/scene_parameter_list.h"

#include "accel/shape_kinds.h"
#include "core/error.h"
#include "core/params/material_parameters.h"
#include "core/params/scene_parameters.h"
#include "integrators/lights/light_kinds.h"
#include "integrators/materials/material_kind.h"
#include "integrators/media/medium_kinds.h"
#include "integrators/scene_params/parameter_path.h"

namespace nx {
namespace {

void addFixed(std::vector<SceneParameterInfo>& out, const std::string& name,
              const std::string& key) {
  const FixedParameter& f = fixedParameter(key);
  out.push_back({name, f.type, f.unit, f.doc, "", f.range, f.differentiable});
}

void addSpec(std::vector<SceneParameterInfo>& out, const std::string& name, const ParamSpec& s,
             const std::string& doc, const std::string& defaultText) {
  out.push_back({name, paramTypeName(s.type), s.unit, doc, defaultText, s.range, s.differentiable});
}

// The fluorescence fields of a material or a dye named `prefix`.
void addFluorescence(std::vector<SceneParameterInfo>& out, const std::string& prefix,
                     const FluorescenceDesc& f, bool dye) {
  if (f.matrixCsv || f.matrix) return addFixed(out, prefix + ".matrix", "fluorescence.matrix");
  if (f.spectra) { // the separable form: its spectra and yield
    for (const char* field : {"absorptance", "emission", "quantum_yield"})
      addFixed(out, prefix + "." + field, std::string("fluorescence.") + field);
    if (!dye) addFixed(out, prefix + ".concentration", "fluorescence.concentration");
    return;
  }
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
void addMaterial(std::vector<SceneParameterInfo>& out, const std::string& label,
                 const MaterialDesc& m) {
  const MaterialKindSpec* kind = findMaterialKind(m.material);
  if (!kind) return;
  for (const KindParameter& p : kind->params) {
    const ParamSpec& spec = *materialParameter(p.name);
    addSpec(out, label + "." + p.name, spec, *p.doc ? p.doc : spec.doc, p.defaultText);
    if (spec.type == ParamType::Fluorescence)
      if (const auto* f = m.params.get<FluorescenceDesc>("fluorescence"))
        addFluorescence(out, label + ".fluorescence", *f, false);
  }
}

// Every parameter a light's or medium's kind takes, named `label.<parameter>` (a dye is listed
// by its fields).
void addTaken(std::vector<SceneParameterInfo>& out, const std::string& label,
              std::span<const TakenParameter> params) {
  for (const TakenParameter& p : params)
    if (p.spec.type != ParamType::Dye)
      addSpec(out, label + "." + p.spec.name, p.spec, p.spec.doc, p.defaultText);
}

void addCamera(std::vector<SceneParameterInfo>& out, const CameraDesc& c) {
  if (!c.extrinsics)
    for (const char* k : {"position", "look_at", "up"})
      addFixed(out, std::string("camera.") + k, std::string("camera.") + k);
  else
    addFixed(out, "camera.extrinsics", "camera.extrinsics");
  addFixed(out, c.intrinsics ? "camera.intrinsics" : "camera.fov",
           c.intrinsics ? "camera.intrinsics" : "camera.fov");
  addFixed(out, "camera.distortion", "camera.distortion");
  addFixed(out, "camera.thin_lens", "camera.thin_lens");
}

void addObject(std::vector<SceneParameterInfo>& out, const std::string& label,
               const ObjectDesc& o) {
  if (const ShapeKindSpec* kind = findShapeKind(o.shape))
    for (const ShapeParameter& p : kind->params())
      addSpec(out, label + "." + p.spec.name, p.spec, p.spec.doc, "");
  addFixed(out, label + ".emission", "object.emission");
  if (o.emission)
    for (const char* f : {"emission_scale", "emission_at", "emission_quantity"})
      addFixed(out, label + "." + f, std::string("object.") + f);
  if (o.materialRef.empty()) addMaterial(out, label, o);
  if (o.medium) {
    if (const MediumKindSpec* kind = findMediumKind(o.medium->kind))
      addTaken(out, label + ".medium", kind->params());
    if (const auto* dye = o.medium->params.get<FluorescenceDesc>("fluorescence")) {
      addFixed(out, label + ".medium.dye_peak", "medium.dye_peak");
      addFluorescence(out, label + ".medium.dye", *dye, true);
    }
  }
}

} // namespace

std::vector<SceneParameterInfo> sceneParameters(const SceneDesc& d) {
  std::vector<SceneParameterInfo> out;
  for (const char* k :
       {"resolution", "mode", "spp", "seed", "depth", "bands", "background", "illuminant", "path"})
    addFixed(out, k, k);
  for (const NamedSpectrumDesc& n : d.spectra)
    addFixed(out, "spectra['" + n.name + "'].value", "spectrum.value");
  addCamera(out, d.camera);
  for (size_t i = 0; i < d.objects.size(); ++i)
    addObject(out, "objects[" + std::to_string(i) + "]", d.objects[i]);
  for (const NamedMaterialDesc& m : d.materials)
    addMaterial(out, "materials['" + m.id + "']", m.material);
  for (size_t i = 0; i < d.lights.size(); ++i)
    if (const LightKindSpec* kind = findLightKind(d.lights[i].kind))
      addTaken(out, "lights[" + std::to_string(i) + "]", kind->params());
  return out;
}

SceneParameterInfo sceneParameter(const SceneDesc& d, const std::string& name) {
  const std::string canonical = canonicalParameterName(name);
  for (SceneParameterInfo& p : sceneParameters(d))
    if (p.name == canonical) return p;
  throw Error("no scene parameter named '" + name + "' (Scene.parameters() lists them)");
}

} // namespace nx
