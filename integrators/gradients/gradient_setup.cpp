#include "integrators/gradients/gradient_setup.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/error.h"
#include "integrators/gradients/shape_setup.h"
#include "integrators/render_scene.h"
#include "integrators/scene_params/parameter_numbers.h"
#include "integrators/scene_params/scene_fields.h"
#include "integrators/scene_params/scene_parameter_list.h"

namespace nx {
namespace {

// `desc` resolved with parameter `name` set to `values`; nullopt when a value is refused.
std::optional<RenderScene> resolvedWith(const SceneDesc& desc, const std::string& name,
                                        std::span<const double> values, bool fluorescence) {
  SceneDesc copy = desc;
  if (!setParameterNumbers(copy, name, values)) return std::nullopt;
  if (!fluorescence) removeFluorescence(copy);
  return resolveRenderScene(copy);
}

// A grid of values (a concentration map, a texture's texels): located by resolving the scene
// with every value moved towards the middle of [0, 1]; one slot per value that moves the scene.
GradientParameter gridParameter(SceneTangents& tangents, const SceneDesc& desc,
                                const std::string& name, const ParameterNumbers& n,
                                const RenderScene& base, bool fluorescence) {
  std::vector<double> moved = n.values;
  for (double& v : moved) v += v < 0.5 ? 1e-3 : -1e-3;
  const std::optional<RenderScene> changed = resolvedWith(desc, name, moved, fluorescence);
  if (!changed) throw Error(name + ": not differentiable: its values cannot be moved");
  GradientParameter p{name, 0, 0, true, n.shape};
  p.firstSlot = n.form == ParameterNumbers::Form::Texture
                    ? addTextureSlots(tangents, name, base, *changed)
                    : addConcentrationSlots(tangents, name, base, *changed);
  p.slots = tangents.slots() - p.firstSlot;
  return p;
}

// A measured matrix's cells: fromMeasured resamples them linearly, so each cell's tangent is
// its column of the resampling map; one resolved copy (every cell scaled down a little, which
// every matrix allows) locates the material. Nullopt where that does not apply (a medium's dye,
// a matrix not resolved as the plain resampling): then per cell.
std::optional<GradientParameter>
measuredMatrixParameter(SceneTangents& tangents, const SceneDesc& desc, const std::string& name,
                        const ParameterNumbers& n, const RenderScene& base, bool fluorescence) {
  const FieldValue field = sceneField(desc, name);
  const auto* matrix = std::get_if<std::shared_ptr<const MeasuredMatrix>>(&field);
  if (!fluorescence || !matrix || !*matrix) return std::nullopt;
  std::vector<double> moved = n.values;
  for (double& v : moved) v *= 1 - 1e-3;
  const std::optional<RenderScene> changed = resolvedWith(desc, name, moved, fluorescence);
  if (!changed) return std::nullopt;
  const std::optional<uint32_t> first =
      addMeasuredCellSlots(tangents, name, base, *changed, measuredResampling(**matrix), n.values);
  if (!first) return std::nullopt;
  return GradientParameter{name, *first, static_cast<uint32_t>(n.values.size()), true, n.shape};
}

// A table's knots where the scene renders the table itself: each knot's tangent is its hat
// (addTableKnotSlots), located by one resolved copy with the knots moved unevenly (an even
// scaling would pass a normalised spectrum as linear). Nullopt where the table reaches more
// (a dye's spectra, a medium's coefficients): then per knot.
std::optional<GradientParameter> tableKnotParameter(SceneTangents& tangents, const SceneDesc& desc,
                                                    const std::string& name,
                                                    const ParameterNumbers& n,
                                                    const RenderScene& base, bool fluorescence) {
  double size = 1e-2;
  for (double v : n.values) size = std::max(size, std::abs(v));
  std::vector<double> moved = n.values;
  for (size_t k = 0; k < moved.size(); ++k)
    moved[k] += 1e-3 * size * static_cast<double>(1 + k % 3);
  const std::optional<RenderScene> changed = resolvedWith(desc, name, moved, fluorescence);
  if (!changed) return std::nullopt;
  const std::optional<uint32_t> first =
      addTableKnotSlots(tangents, name, base, *changed, n.values, moved);
  if (!first) return std::nullopt;
  return GradientParameter{name, *first, static_cast<uint32_t>(n.values.size()), true, {}};
}

// Written back as its numbers, the parameter must give the scene it is (a table's
// extrapolate="..." is not one of its numbers): else the derivative would be another scene's.
void requireNumbersGiveTheScene(const SceneDesc& desc, const std::string& name,
                                const ParameterNumbers& n, const RenderScene& base,
                                bool fluorescence) {
  const std::optional<RenderScene> same = resolvedWith(desc, name, n.values, fluorescence);
  if (!same) throw Error(name + ": not differentiable: its value is refused when set back");
  SceneTangents check = SceneTangents::sizedFor(base);
  const RenderScene* pair[] = {&*same, &base};
  const double unit[] = {1.0, -1.0};
  try {
    addTangentSlot(check, name, base, pair, unit);
  } catch (const Error&) {
    check.inert.clear();
  }
  if (check.inert.empty())
    throw Error(name + ": not differentiable as written: set as its numbers it renders "
                       "differently (e.g. a table's extrapolate=\"hold\" is not one of its "
                       "numbers); write the table without it");
}

// One slot for number j of the parameter: central differences where both sides are allowed,
// else one-sided of second order.
void addNumberSlot(SceneTangents& tangents, const SceneDesc& desc, const std::string& name,
                   const ParameterNumbers& n, size_t j, const RenderScene& base,
                   bool fluorescence) {
  const double v = n.values[j];
  const double h = 1e-3 * std::max(std::abs(v), 1e-2);
  auto with = [&](double x) {
    std::vector<double> values = n.values;
    values[j] = x;
    return resolvedWith(desc, name, values, fluorescence);
  };
  std::vector<std::optional<RenderScene>> s;
  std::vector<double> w;
  if (auto a = with(v + h), b = with(v - h); a && b) {
    s = {std::move(a), std::move(b)};
    w = {0.5 / h, -0.5 / h};
  } else if (auto c = with(v), a2 = with(v - h), b2 = with(v - 2 * h); c && a2 && b2) {
    s = {std::move(c), std::move(a2), std::move(b2)};
    w = {1.5 / h, -2 / h, 0.5 / h};
  } else if (auto c3 = with(v), a3 = with(v + h), b3 = with(v + 2 * h); c3 && a3 && b3) {
    s = {std::move(c3), std::move(a3), std::move(b3)};
    w = {-1.5 / h, 2 / h, -0.5 / h};
  } else {
    throw Error(name + ": cannot differentiate at " + std::to_string(v) + ": no step of " +
                std::to_string(h) + " either way is allowed");
  }
  std::vector<const RenderScene*> scenes;
  for (const auto& x : s) scenes.push_back(&*x);
  addTangentSlot(tangents, n.indexed() ? name + "[" + std::to_string(j) + "]" : name, base, scenes,
                 w);
}

} // namespace

GradientSetup gradientSetup(const SceneDesc& desc, const std::vector<std::string>& names,
                            const RenderScene& base, bool fluorescence) {
  GradientSetup r;
  r.tangents = SceneTangents::sizedFor(base);
  for (const std::string& given : names) {
    const SceneParameterInfo info = sceneParameter(desc, given);
    const std::string& name = info.name;
    // Which parameters are differentiable: their declarations say.
    if (!info.differentiable)
      throw Error(name + ": not differentiated: its declaration does not say differentiable "
                         "(scene.parameters() marks those that are; docs/inverse.md)");
    for (const GradientParameter& p : r.parameters)
      if (p.name == name) throw Error("gradients: '" + name + "' given twice");
    if (auto shape = shapeParameter(r.tangents, desc, name, base)) {
      r.parameters.push_back(std::move(*shape));
      continue;
    }
    const ParameterNumbers n = parameterNumbers(desc, name);
    if (n.grid()) {
      r.parameters.push_back(gridParameter(r.tangents, desc, name, n, base, fluorescence));
      continue;
    }
    GradientParameter p{name, r.tangents.slots(), static_cast<uint32_t>(n.values.size()),
                        n.indexed(),
                        n.form == ParameterNumbers::Form::Matrix ? n.shape : std::vector<long>{}};
    if (n.indexed()) requireNumbersGiveTheScene(desc, name, n, base, fluorescence);
    if (n.form == ParameterNumbers::Form::Matrix)
      if (auto cells = measuredMatrixParameter(r.tangents, desc, name, n, base, fluorescence)) {
        r.parameters.push_back(std::move(*cells));
        continue;
      }
    if (n.form == ParameterNumbers::Form::Table)
      if (auto knots = tableKnotParameter(r.tangents, desc, name, n, base, fluorescence)) {
        r.parameters.push_back(std::move(*knots));
        continue;
      }
    for (size_t j = 0; j < n.values.size(); ++j)
      addNumberSlot(r.tangents, desc, name, n, j, base, fluorescence);
    r.parameters.push_back(p);
  }
  if (r.parameters.empty()) throw Error("gradients: expected at least one name");
  r.warnings = shapeCoverageWarnings(base, r.tangents);
  return r;
}

} // namespace nx
