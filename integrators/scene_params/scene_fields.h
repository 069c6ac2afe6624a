#pragma once
// Get and set by name the scene parameters that are fields of the description rather than a
// kind's parameters (core/params/scene_parameters.h declares them: the settings, the camera,
// an object's emission, the fluorescence model's fields, a medium's dye peak, a named
// spectrum's values). Setting checks what the value must be in its place (the camera as the
// build checks it, a required field, what an emission's quantity needs); the value's own type
// and range are the declaration's, which callers convert by (Python: py_scene_fields.cpp).

#include <memory>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "core/error.h"
#include "io/scene_desc.h"
#include "spectra/reradiation_matrix.h"

namespace nx {

/// The value of such a field: absent (None), a number (integers too), numbers, text, a point,
/// a spectrum, a measured matrix or a concentration map.
using FieldValue =
    std::variant<std::monostate, double, std::vector<double>, std::string, Vec3d, SpectrumDesc,
                 std::shared_ptr<const MeasuredMatrix>, std::shared_ptr<const ConcentrationMap>>;

/// A value of the wrong kind for its place (None where a number is required): Python's
/// TypeError; other refusals are nx::Error (ValueError).
class FieldTypeError : public Error {
public:
  using Error::Error;
};

/// The value of `d`'s field parameter `name` ("spp", "camera.fov", "objects[1].emission_at",
/// "materials['card'].fluorescence.stokes_nm", ...). Throws nx::Error for a name that is not
/// one, or whose item has no such field (an object without fluorescence).
FieldValue sceneField(const SceneDesc& d, const std::string& name);

/// The file field parameter `name`'s value is read from (a measured matrix's or a
/// concentration map's CSV, when the scene names one rather than holding numbers), or "".
std::string sceneFieldFile(const SceneDesc& d, const std::string& name);

/// Sets `d`'s field parameter `name` to `v`, checked in its place; a refused value leaves `d`
/// as it was. Errors name the parameter: "camera.position: the camera is placed by
/// <extrinsics>".
void setSceneField(SceneDesc& d, const std::string& name, const FieldValue& v);

/// The declaration key of field parameter `name` in core/params/scene_parameters.h
/// ("objects[1].medium.dye.stokes_nm" -> "fluorescence.stokes_nm"), or "" if it is not one.
std::string sceneFieldKey(const std::string& name);

} // namespace nx
