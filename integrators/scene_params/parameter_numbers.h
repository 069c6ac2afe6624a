#pragma once
// The numbers of a scene parameter, read and written by name: what a differentiated render
// moves (integrators/gradients/gradient_setup.h) and what Python's gradient code reads. A
// parameter's numbers are one number, a colour's channels, a table's values (its wavelengths
// kept), a measured matrix's cells, a texture's texels or a concentration map's values.

#include <span>
#include <string>
#include <vector>

#include "io/scene_desc.h"

namespace nx {

/// A parameter's numbers and their form.
struct ParameterNumbers {
  enum class Form {
    Number,        ///< one number
    List,          ///< a colour's channels
    Table,         ///< a tabulated spectrum's values (at its wavelengths)
    Matrix,        ///< a measured matrix's cells, excitation by emission
    Texture,       ///< a texture's texels, (height, width, bands)
    Concentration, ///< a concentration map, (height, width)
    Rows           ///< rows of reals (a mesh's vertices), (rows, columns)
  };
  Form form = Form::Number;
  std::vector<double> values;
  std::vector<long> shape; ///< Matrix, Texture, Concentration, Rows: the values' shape
  /// One slot per number (a list, a table, a grid), rather than a single number.
  bool indexed() const { return form != Form::Number; }
  /// A grid of values (a texture, a concentration map): located per value, not per number.
  bool grid() const { return form == Form::Texture || form == Form::Concentration; }
};

/// The numbers of `d`'s parameter `name`. Throws nx::Error naming it when it has none as given
/// (not a scene parameter, not given, a named or built-in spectrum, a file's table).
ParameterNumbers parameterNumbers(const SceneDesc& d, const std::string& name);

/// Sets `d`'s parameter `name` to `values` (as many as parameterNumbers gives, in its form),
/// each checked as a value set from Python is (its range; a spectrum's values not negative; a
/// colour's channels, a texture's texels and a map's values in [0, 1]; a matrix as a measured
/// one). Returns false, leaving
/// `d` as it was, when a value is refused; throws nx::Error for a wrong count or a parameter
/// without numbers.
bool setParameterNumbers(SceneDesc& d, const std::string& name, std::span<const double> values);

} // namespace nx
