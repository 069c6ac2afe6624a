#pragma once
// A scene parameter's name as steps: "objects[1].fluorescence.stokes_nm" -> (objects, 1),
// (fluorescence), (stokes_nm); "materials['card'].reflectance" -> (materials, 'card'),
// (reflectance). The names Scene.parameters() lists and Scene.edits records
// (scene_parameter_list.h).

#include <cstddef>
#include <string>
#include <variant>
#include <vector>

namespace nx {

/// One step of a parameter's name: an attribute and, for a list or a mapping, its index or key.
struct ParameterStep {
  std::string attribute;
  std::variant<std::monostate, size_t, std::string> index; ///< none, [i] or ['key']
};

/// The steps of `name`; throws nx::Error "no scene parameter named '...'" if it is not of the
/// form attribute[index].attribute... (the last step has no index).
std::vector<ParameterStep> parameterSteps(const std::string& name);

/// `name` spelled as parameters are listed: keys in single quotes (materials["x"] ->
/// materials['x']).
std::string canonicalParameterName(std::string name);

} // namespace nx
