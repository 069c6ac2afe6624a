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

/// Where an object's or light's view is: its item's position now (py_scene_items.h); an item
/// that left its list is refused, naming how it left.
template <class Desc>
size_t itemPosition(ItemRegistry<Desc>& items, const ItemIdentity<Desc>& item, size_t n,
                    const char* noun, const char* list) {
  if (const auto p = items.position(item.id, n)) return *p;
  throw py::value_error(item.leftAs + ": this " + noun + " is no longer in the scene (" + item.how +
                        "); take scene." + list + "[...] again");
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
  std::shared_ptr<ItemIdentity<nx::LightDesc>> item;
  size_t position() const {
    return itemPosition(s->lightItems, *item, s->desc.lights.size(), "light", "lights");
  }
  nx::LightDesc& get() const { return s->desc.lights[position()]; }
  /// The light as it is, or as it was when it left the scene (to be copied).
  const nx::LightDesc& value() const { return item->former ? *item->former : get(); }
  std::string label() const {
    return item->former ? item->leftAs : "lights[" + std::to_string(position()) + "]";
  }
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
  size_t i;                                           ///< a named material's position
  std::shared_ptr<ItemIdentity<nx::ObjectDesc>> item; ///< an object's own material: the object
  nx::ObjectDesc& object() const {
    return s->desc
        .objects[itemPosition(s->objectItems, *item, s->desc.objects.size(), "object", "objects")];
  }
  nx::MaterialDesc& get() const {
    return named ? s->desc.materials.at(i).material : static_cast<nx::MaterialDesc&>(object());
  }
  std::string label() const {
    if (named) return "materials['" + s->desc.materials.at(i).id + "']";
    if (item->former) return item->leftAs;
    return "objects[" +
           std::to_string(
               itemPosition(s->objectItems, *item, s->desc.objects.size(), "object", "objects")) +
           "]";
  }
  nx::SourceLocation loc() const { return named ? s->desc.materials.at(i).loc : object().loc; }
  // An object using a <material id> has no parameters of its own.
  nx::MaterialDesc& editable() const {
    if (!named && !object().materialRef.empty())
      throw py::value_error(label() + ": uses the material '" + object().materialRef +
                            "'; change scene.materials['" + object().materialRef + "'] instead");
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
  std::shared_ptr<ItemIdentity<nx::ObjectDesc>> item;
  size_t position() const {
    return itemPosition(s->objectItems, *item, s->desc.objects.size(), "object", "objects");
  }
  nx::ObjectDesc& get() const { return s->desc.objects[position()]; }
  /// The object as it is, or as it was when it left the scene (to be copied).
  const nx::ObjectDesc& value() const { return item->former ? *item->former : get(); }
  std::string label() const {
    return item->former ? item->leftAs : "objects[" + std::to_string(position()) + "]";
  }
  MaterialView material() const {
    const nx::ObjectDesc& o = get();
    if (!o.materialRef.empty())
      for (size_t k = 0; k < s->desc.materials.size(); ++k)
        if (s->desc.materials[k].id == o.materialRef) return {s, true, k, nullptr};
    return {s, false, 0, item};
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
