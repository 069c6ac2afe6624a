#pragma once
// The views nxrender.Scene hands out (scene.objects[i], .material, .medium, .camera, ...): a
// scene's shared state and where in it the item is. A view of an object or a light names a
// position: once objects or lights are inserted or removed, older views refuse to be used
// (they could name another item by then).

#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "apps/python/py_scene.h"
#include "integrators/lights/light_kinds.h"
#include "integrators/media/medium_kinds.h"

namespace nxpy {

using StatePtr = std::shared_ptr<SceneState>;

/// The error of a view used after its list changed.
inline py::value_error staleView(const std::string& label, const char* list) {
  return py::value_error(label + ": this view was taken before " + list +
                         " were inserted into or removed from the scene; take scene." + list +
                         "[...] again");
}

struct CameraView {
  StatePtr s;
};

/// A <spectrum name="..."> of the scene.
struct NamedSpectrumView {
  StatePtr s;
  size_t i;
  nx::NamedSpectrumDesc& get() const { return s->desc.spectra.at(i); }
  std::string label() const { return "spectra['" + get().name + "']"; }
};

struct LightView {
  StatePtr s;
  size_t i;
  uint64_t version; ///< the scene's lightsVersion when it was taken
  nx::LightDesc& get() const {
    if (s->lightsVersion != version) throw staleView(label(), "lights");
    return s->desc.lights.at(i);
  }
  std::string label() const { return "lights[" + std::to_string(i) + "]"; }
  // What bindTakenParameters asks of a view.
  nx::ParameterSet& params() const { return get().params; }
  std::string kindText() const { return "a " + get().kind + " light"; }
  const nx::TakenParameter* declared(const std::string& name) const {
    const nx::LightKindSpec* k = nx::findLightKind(get().kind);
    return k ? nx::lightParameter(*k, name) : nullptr;
  }
  nx::SourceLocation loc() const { return get().loc; }
  SceneState& state() const { return *s; }
};

struct MaterialView {
  StatePtr s;
  bool named;
  size_t i;
  uint64_t version = 0; ///< an object's: the scene's objectsVersion when it was taken
  nx::MaterialDesc& get() const {
    if (!named && s->objectsVersion != version) throw staleView(label(), "objects");
    return named ? s->desc.materials.at(i).material
                 : static_cast<nx::MaterialDesc&>(s->desc.objects.at(i));
  }
  std::string label() const {
    return named ? "materials['" + s->desc.materials.at(i).id + "']"
                 : "objects[" + std::to_string(i) + "]";
  }
  nx::SourceLocation loc() const {
    return named ? s->desc.materials.at(i).loc : s->desc.objects.at(i).loc;
  }
  // An object using a <material id> has no parameters of its own.
  nx::MaterialDesc& editable() const {
    if (!named && !s->desc.objects.at(i).materialRef.empty())
      throw py::value_error(label() + ": uses the material '" + s->desc.objects.at(i).materialRef +
                            "'; change scene.materials['" + s->desc.objects.at(i).materialRef +
                            "'] instead");
    return get();
  }
};

struct FluorescenceView {
  MaterialView m;
  nx::FluorescenceDesc& get() const {
    nx::FluorescenceDesc* f = m.get().params.getMutable<nx::FluorescenceDesc>("fluorescence");
    if (!f) throw py::value_error(m.label() + ": has no fluorescence any more");
    return *f;
  }
  nx::FluorescenceDesc& editable(const char* field) const {
    nx::FluorescenceDesc& f = get();
    (void)m.editable();
    if (f.eem) { // an imported EEM: its yield and peak absorptance, when the scene gave them
      const std::string name = field;
      if ((name == "quantum_yield" && f.eem->referenceFile.empty()) ||
          (name == "peak_absorptance" && !f.eem->absorptance))
        return f;
      throw py::value_error(
          m.label() + ".fluorescence." + field + ": the fluorescence is the EEM " + f.eem->file +
          (name == "quantum_yield" || name == "peak_absorptance"
               ? std::string(" whose ") + field + " comes from its <reference> or <absorptance>"
               : "; only quantum_yield and peak_absorptance of an "
                 "EEM are set from Python"));
    }
    if (f.matrixCsv || f.matrix)
      throw py::value_error(m.label() + ".fluorescence." + field +
                            ": the fluorescence is a measured matrix" +
                            (f.matrixCsv ? " (" + *f.matrixCsv + ")" : std::string()) +
                            "; set a model with set_fluorescence(...) first");
    return f;
  }
  /// The name its fields are recorded under ("objects[1].fluorescence").
  std::string prefix() const { return m.label() + ".fluorescence"; }
  SceneState& state() const { return *m.s; }
};

struct ObjectView {
  StatePtr s;
  size_t i;
  uint64_t version; ///< the scene's objectsVersion when it was taken
  nx::ObjectDesc& get() const {
    if (s->objectsVersion != version) throw staleView(label(), "objects");
    return s->desc.objects.at(i);
  }
  std::string label() const { return "objects[" + std::to_string(i) + "]"; }
  MaterialView material() const {
    const nx::ObjectDesc& o = get();
    if (!o.materialRef.empty())
      for (size_t k = 0; k < s->desc.materials.size(); ++k)
        if (s->desc.materials[k].id == o.materialRef) return {s, true, k};
    return {s, false, i, version};
  }
};

struct MediumView {
  ObjectView o;
  nx::MediumDesc& get() const {
    auto& m = o.get().medium;
    if (!m) throw py::value_error(o.label() + ": has no medium any more");
    return *m;
  }
  std::string label() const { return o.label() + ".medium"; }
  // What bindTakenParameters asks of a view.
  nx::ParameterSet& params() const { return get().params; }
  std::string kindText() const { return "a " + get().kind + " medium"; }
  const nx::TakenParameter* declared(const std::string& name) const {
    const nx::MediumKindSpec* k = nx::findMediumKind(get().kind);
    return k ? nx::mediumParameter(*k, name) : nullptr;
  }
  nx::SourceLocation loc() const { return get().loc; }
  SceneState& state() const { return *o.s; }
};

// The fluorescent dye dissolved in a medium: the parametric model's fields (its peak is the
// medium's dye_peak, a coefficient per unit length).
struct DyeView {
  MediumView v;
  nx::FluorescenceDesc& get() const {
    nx::FluorescenceDesc* f = v.get().params.getMutable<nx::FluorescenceDesc>("fluorescence");
    if (!f) throw py::value_error(v.label() + ": has no dye any more");
    return *f;
  }
  nx::FluorescenceDesc& editable(const char*) const { return get(); }
  std::string prefix() const { return v.label() + ".dye"; }
  SceneState& state() const { return *v.o.s; }
};

} // namespace nxpy
