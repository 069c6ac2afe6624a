#pragma once
// A scene as data: nested dictionaries and lists of numbers, strings and arrays keyed by the
// scene format's own element and parameter names (docs/reference), one to one. What
// Scene.from_dict takes and Scene.to_dict gives (Python's dicts and numpy arrays convert to it
// generically); io/scene_tree_text.h turns it into scene text, read by the one scene reader.

#include <cstddef>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace nx {

/// One value of a scene tree.
struct SceneTree {
  /// Numbers with a shape (a numpy array): rows x columns (columns 0: one-dimensional).
  struct Array {
    enum class Kind { Float32, Float64, Integer };
    std::vector<double> values;
    size_t rows = 0, columns = 0;
    Kind kind = Kind::Float64;
  };
  using List = std::vector<SceneTree>;
  /// Keys in the order given.
  using Dict = std::vector<std::pair<std::string, SceneTree>>;
  /// None (absent), a truth value, a number, a string, an array, a list or a dictionary.
  std::variant<std::monostate, bool, double, std::string, Array, List, Dict> value;

  SceneTree() = default;
  /// A tree holding `v`.
  template <typename T>
  SceneTree(T v) : value(std::move(v)) {} // NOLINT: implicit, as a value of the variant

  /// The value if it is a T, else null.
  template <typename T>
  const T* as() const {
    return std::get_if<T>(&value);
  }
  /// The entry `key` of a dictionary, or null (not a dictionary, or no such key).
  const SceneTree* find(const std::string& key) const;
};

/// What a value is, for messages ("a number", "a list of 3", "a dictionary", ...).
std::string describe(const SceneTree& t);

} // namespace nx
