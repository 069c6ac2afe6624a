#pragma once
// Named, typed parameters as a scene gives them (Mitsuba 3's Properties, pbrt-v4's
// ParameterDictionary): each with its value and file:line, in the order written. A material is
// a kind and one of these; the kind's schema (integrators/materials/material_kinds.h) says which
// names it takes, and every name it does not take is an error.

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/params/scene_limits.h"
#include "core/params/scene_values.h"
#include "core/vec3.h"

namespace nx {

/// What a parameter's value is (its XML syntax, its Python form).
enum class ParamType : uint8_t {
  Number,       ///< one number within the parameter's range
  Rgb,          ///< R, G, B[, A], non-negative (within the range where there is one)
  Spectrum,     ///< a name, a number, nm:value pairs or csv="file"
  Reflectance,  ///< a Spectrum, or texture="colorchecker" / a spectral EXR / a PNG or JPEG
  Ior,          ///< a number, a named glass or a dispersion formula
  Fluorescence, ///< the re-radiation model's parameters or a measured matrix
  Coating,      ///< a thin film: thickness in nm and an index of refraction
  Name,         ///< a word from a list (e.g. a built-in metal)
  Point,        ///< x, y, z within 1e12 (scene units)
  File,         ///< a file name, relative to the scene file
  Transform,    ///< <translate>, <rotate>, <scale> and <matrix> steps: an affine map
  Dye,          ///< a medium's dye: the fluorescence model with <peak> per unit length
  Reals,        ///< rows of `columns` finite numbers (kept as float), e.g. a mesh's vertices
  Indices,      ///< rows of `columns` whole numbers in [0, 2^32), e.g. a mesh's faces
};

/// Calls f with each space-separated word of `words` (a ParamSpec's excludes).
template <typename F>
void forEachWord(const char* words, F&& f) {
  std::string word;
  for (const char* c = words;; ++c) {
    if (*c == ' ' || *c == '\0') {
      if (!word.empty()) f(word);
      word.clear();
      if (*c == '\0') return;
    } else {
      word += *c;
    }
  }
}

/// The type's name in reference docs and errors ("number", "spectrum", ...).
const char* paramTypeName(ParamType t);

/// The scene format's declaration of one parameter name: its type, unit, range and meaning.
/// A name has one type wherever it is used; kinds choose which names they take.
struct ParamSpec {
  const char* name;            ///< the element name (<roughness>) and Python key
  ParamType type;              ///< how its value is written
  const char* unit;            ///< "nm", "1" (dimensionless), ...
  const ParameterRange* range; ///< Number: the allowed values; null otherwise
  const char* doc;             ///< one line for the reference docs
  const char* example;         ///< a valid value as a scene writes it (element content)
  /// Names that cannot be given with it, space-separated ("" : none): setting it from Python
  /// removes them (a <metal> replaces <eta> and <k>).
  const char* excludes = "";
  /// Point: what its three numbers are in errors ("" : "x, y, z"); File given as an attribute:
  /// what the file is ("a .ply or .obj mesh").
  const char* what = "";
  /// Reals and Indices: the numbers per row (3 for x, y, z; 2 for u, v).
  uint32_t columns = 0;
  /// Renders can differentiate with respect to it (render(gradients=...), nxrender.backward);
  /// declared with differentiable(...).
  bool differentiable = false;
};

/// `s` declared differentiable (renders give derivatives with respect to it).
constexpr ParamSpec differentiable(ParamSpec s) {
  s.differentiable = true;
  return s;
}

/// One parameter a light or medium kind takes: its declaration, its default, whether it is
/// required. A Spectrum parameter NAME may have a factor NAME_scale, written as its
/// scale="..." attribute.
struct TakenParameter {
  ParamSpec spec;          ///< name, type, unit, range, meaning, example
  const char* defaultText; ///< its default as a scene would write it ("": none)
  bool required = false;   ///< the item cannot be built without it
};

/// A parameter's value, by type (Number -> double, Rgb -> array, Spectrum and Reflectance ->
/// SpectrumDesc, Ior -> IorDesc, Fluorescence and Dye -> FluorescenceDesc, Coating -> CoatingDesc,
/// Name and File -> string, Point -> Vec3d, Transform -> AffineDesc, Reals and Indices ->
/// ArrayDesc).
using ParamValue =
    std::variant<double, std::array<double, 4>, SpectrumDesc, IorDesc, FluorescenceDesc,
                 CoatingDesc, std::string, Vec3d, AffineDesc, ArrayDesc>;

/// One parameter as given.
struct Parameter {
  std::string name;
  ParamValue value;
  SourceLocation loc;
};

/// The parameters of one item, in the order written, each name at most once.
class ParameterSet {
public:
  /// The parameter called `name`, or null.
  const Parameter* find(std::string_view name) const;
  /// Its value if present and of type T, else null.
  template <typename T>
  const T* get(std::string_view name) const {
    const Parameter* p = find(name);
    return p ? std::get_if<T>(&p->value) : nullptr;
  }
  /// The same, editable (Python edits a fluorescence model's fields in place).
  template <typename T>
  T* getMutable(std::string_view name) {
    const Parameter* p = find(name);
    return p ? std::get_if<T>(&const_cast<Parameter*>(p)->value) : nullptr;
  }
  /// A number if present.
  std::optional<double> number(std::string_view name) const {
    const double* v = get<double>(name);
    return v ? std::optional<double>(*v) : std::nullopt;
  }
  /// Whether `name` is given.
  bool has(std::string_view name) const { return find(name) != nullptr; }
  /// Where `name` was given (`fallback` if it was not).
  const SourceLocation& locOf(std::string_view name, const SourceLocation& fallback) const;
  /// Sets (replacing) a parameter, keeping its place if it was given.
  void set(Parameter p);
  /// Removes a parameter (nothing if absent).
  void erase(std::string_view name);
  /// The parameters in the order written.
  const std::vector<Parameter>& items() const { return items_; }
  bool empty() const { return items_.empty(); }

  /// Every parameter and its value in one canonical text (sorted by name, numbers with 17
  /// digits, locations left out): equal texts are the same parameters. The one serialisation
  /// of parameters (material sharing, identity hashes).
  std::string canonicalText() const;

private:
  std::vector<Parameter> items_;
};

/// The canonical text of one value (see ParameterSet::canonicalText).
std::string canonicalText(const ParamValue& v);

} // namespace nx
