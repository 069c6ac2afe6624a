#pragma once
// The scene's field parameters (core/params/scene_parameters.h: settings, camera, emission,
// fluorescence fields, a dye's peak, a named spectrum's values) as Python properties, bound
// generically: one property per declaration, its value converted by the declared type and
// range, read and set by name through the library (integrators/scene_params/scene_fields.h),
// and recorded as an edit.

#include <pybind11/pybind11.h>

#include <algorithm>
#include <initializer_list>
#include <string>

#include "apps/python/py_scene.h"
#include "apps/python/py_scene_views.h"
#include "core/params/scene_parameters.h"
#include "integrators/scene_params/scene_fields.h"

namespace nxpy {

/// The Python form of field value `v` declared as `decl`.
py::object fieldToPython(const nx::FixedParameter& decl, const nx::FieldValue& v);

/// `value` as a field value declared as `decl`, checked by its type and range; errors name
/// `param` (TypeError, ValueError).
nx::FieldValue fieldFromPython(const nx::FixedParameter& decl, const py::handle& value,
                               const std::string& param, const nx::SourceLocation& loc);

/// A measured matrix from Python: (excitation_nm, emission_nm, values[excitation, emission]),
/// its shape checked (TypeError, ValueError naming `param`); its cells are checked by the caller.
std::shared_ptr<const nx::MeasuredMatrix> matrixFromPython(const py::handle& value,
                                                           const std::string& param);

/// How setting a measured matrix is recorded: its size and the digest of its content.
std::string matrixEditText(const nx::MeasuredMatrix& m);

/// Reads `state`'s field parameter `name` (nxrender.Error where its file cannot be read).
py::object getField(const SceneState& state, const std::string& name);

/// Sets `state`'s field parameter `name` from Python, checked by the library in its place, and
/// records the edit; a refused value changes nothing.
void setField(SceneState& state, const std::string& name, const py::handle& value);

/// The name each view gives its fields ("camera", "objects[1].fluorescence", "" for the scene)
/// and its scene's state; both refuse a view taken before its list changed.
inline std::string fieldPrefix(const PyScene&) {
  return "";
}
inline SceneState& stateOf(const PyScene& s) {
  return *s.state;
}
inline std::string fieldPrefix(const CameraView&) {
  return "camera";
}
inline SceneState& stateOf(const CameraView& c) {
  return *c.s;
}
inline std::string fieldPrefix(const NamedSpectrumView& v) {
  return v.label();
}
inline SceneState& stateOf(const NamedSpectrumView& v) {
  return *v.s;
}
inline std::string fieldPrefix(const ObjectView& o) {
  return (void)o.get(), o.label();
}
inline SceneState& stateOf(const ObjectView& o) {
  return (void)o.get(), *o.s;
}
inline std::string fieldPrefix(const MediumView& m) {
  return (void)m.get(), m.label();
}
inline SceneState& stateOf(const MediumView& m) {
  return *m.o.s;
}
inline std::string fieldPrefix(const FluorescenceView& f) {
  return (void)f.get(), f.prefix();
}
inline SceneState& stateOf(const FluorescenceView& f) {
  return f.state();
}
inline std::string fieldPrefix(const DyeView& d) {
  return (void)d.get(), d.prefix();
}
inline SceneState& stateOf(const DyeView& d) {
  return d.state();
}

/// One property per declaration whose key is `kind`.LEAF (or has no dot, kind ""), named LEAF,
/// except the leaves in `except`.
template <class View>
void bindSceneFields(py::class_<View>& c, const std::string& kind,
                     std::initializer_list<const char*> except = {}) {
  for (const nx::FixedParameter& f : nx::fixedParameters()) {
    const std::string key = f.key;
    const size_t dot = key.find('.');
    const std::string k = dot == std::string::npos ? "" : key.substr(0, dot);
    const std::string leaf = dot == std::string::npos ? key : key.substr(dot + 1);
    if (k != kind ||
        std::any_of(except.begin(), except.end(), [&](const char* x) { return leaf == x; }))
      continue;
    // The view's name for it and its scene's state (fieldPrefix and stateOf check the view is
    // still valid).
    auto nameOf = [leaf](const View& v) {
      const std::string prefix = fieldPrefix(v);
      return prefix.empty() ? leaf : prefix + "." + leaf;
    };
    c.def_property(
        leaf.c_str(), [nameOf](const View& v) { return getField(stateOf(v), nameOf(v)); },
        [nameOf](const View& v, const py::object& value) {
          setField(stateOf(v), nameOf(v), value);
        },
        f.doc);
  }
}

} // namespace nxpy
