#include "io/scene_tree_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <set>

#include "core/error.h"
#include "core/number_text.h"

namespace nx {

const SceneTree* SceneTree::find(const std::string& key) const {
  if (const Dict* d = as<Dict>())
    for (const auto& [k, v] : *d)
      if (k == key) return &v;
  return nullptr;
}

std::string describe(const SceneTree& t) {
  if (t.as<std::monostate>()) return "None";
  if (t.as<bool>()) return "a truth value";
  if (t.as<double>()) return "a number";
  if (const std::string* s = t.as<std::string>()) return "the string '" + *s + "'";
  if (const auto* a = t.as<SceneTree::Array>())
    return "an array of " + std::to_string(a->values.size()) + " numbers";
  if (const auto* l = t.as<SceneTree::List>()) return "a list of " + std::to_string(l->size());
  return "a dictionary";
}

namespace {

using Dict = SceneTree::Dict;
using List = SceneTree::List;
using Array = SceneTree::Array;
using Names = std::set<std::string>;

// Attributes a spectrum's element takes (and so any parameter's element not listed below).
const Names kSpectrumAttributes{"csv",     "column", "extrapolate", "negative",
                                "texture", "scale",  "at",          "quantity"};
// Suffixes NAME_<a> of a key that are attribute <a> of the sibling element NAME (Python's
// emission_scale is <emission scale="...">).
const char* const kAttributeSuffixes[] = {"scale", "at", "quantity", "group"};
// Keys whose values are rows of numbers, never (wavelengths, values) pairs.
const Names kRowKeys{"vertices", "faces", "normals", "uv", "transform", "matrix"};
// Rows of real numbers kept as float (a mesh's): written as the float each number rounds to,
// exactly as numbers set from Python are rounded (one rounding, not two through decimal text).
const Names kFloatRowKeys{"vertices", "normals", "uv"};

// The attributes an element takes, by its tag (objects: kObjectAttributes).
const Names& attributesOf(const std::string& tag) {
  static const Names camera{"calibration", "view"}, light{"type", "group"}, material{"id", "type"},
      medium{"type"}, eem{"file",         "layout",      "units",       "rayleigh_width",
                          "second_order", "raman_shift", "raman_width", "emission_shape"},
      reference{"file", "yield", "absorptance", "excitation"},
      sensor{"csv", "gaussian", "fwhm", "boxes", "centres"},
      background =
          [] {
            Names n = kSpectrumAttributes;
            n.insert("group");
            return n;
          }(),
      spectrum =
          [] {
            Names n = kSpectrumAttributes;
            n.insert("name");
            return n;
          }(),
      none;
  if (tag == "camera") return camera;
  if (tag == "light") return light;
  if (tag == "material") return material;
  if (tag == "medium") return medium;
  if (tag == "eem") return eem;
  if (tag == "reference") return reference;
  if (tag == "sensor") return sensor;
  if (tag == "background") return background;
  if (tag == "spectrum") return spectrum;
  if (tag == "settings" || tag == "fluorescence" || tag == "transform" || tag == "coating")
    return none;
  return kSpectrumAttributes;
}
const Names kObjectAttributes{"name", "group", "file"};

std::string escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&')
      out += "&amp;";
    else if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

// The shortest text that reads back to v (as a float for Float32 arrays).
std::string numberText(double v, Array::Kind kind) {
  return kind == Array::Kind::Float32 ? nx::shortestText(static_cast<float>(v))
                                      : nx::shortestText(v);
}

bool isNumber(const SceneTree& t) {
  return t.as<double>() != nullptr;
}

// Whether t is numbers only: a number, an array, or (nested) lists of them.
bool isNumeric(const SceneTree& t) {
  if (isNumber(t) || t.as<Array>()) return true;
  if (const List* l = t.as<List>())
    return !l->empty() && std::all_of(l->begin(), l->end(), isNumeric);
  return false;
}

// Appends the numbers of t, flattened (asFloat: real numbers as the floats they round to).
void flatten(const SceneTree& t, std::vector<std::string>& out, bool asFloat = false) {
  const auto kindOf = [&](Array::Kind k) {
    return asFloat && k != Array::Kind::Integer ? Array::Kind::Float32 : k;
  };
  if (const double* d = t.as<double>()) out.push_back(numberText(*d, kindOf(Array::Kind::Float64)));
  if (const Array* a = t.as<Array>())
    for (double v : a->values) out.push_back(numberText(v, kindOf(a->kind)));
  if (const List* l = t.as<List>())
    for (const SceneTree& x : *l) flatten(x, out, asFloat);
}

// Numbers as text: rows (the outer list's items, an array's rows) separated by commas.
std::string numbersText(const SceneTree& t, bool asFloat = false) {
  std::string out;
  auto row = [&](const std::vector<std::string>& numbers) {
    if (!out.empty()) out += ", ";
    for (size_t i = 0; i < numbers.size(); ++i) out += (i ? " " : "") + numbers[i];
  };
  if (const Array* a = t.as<Array>()) {
    const size_t width = a->columns ? a->columns : 1;
    std::vector<std::string> r;
    for (size_t i = 0; i < a->values.size(); ++i) {
      r.push_back(numberText(a->values[i], asFloat && a->kind != Array::Kind::Integer
                                               ? Array::Kind::Float32
                                               : a->kind));
      if (r.size() == width || a->columns == 0) row(r), r.clear();
    }
    return out;
  }
  if (const List* l = t.as<List>()) {
    for (const SceneTree& x : *l) {
      std::vector<std::string> r;
      flatten(x, r, asFloat);
      row(r);
    }
    return out;
  }
  std::vector<std::string> r;
  flatten(t, r, asFloat);
  row(r);
  return out;
}

// (wavelengths, values): two numeric sequences of one length (at least 2).
bool isPairs(const SceneTree& t) {
  const List* l = t.as<List>();
  if (!l || l->size() != 2 || !isNumeric((*l)[0]) || !isNumeric((*l)[1])) return false;
  std::vector<std::string> a, b;
  flatten((*l)[0], a), flatten((*l)[1], b);
  return a.size() == b.size() && a.size() >= 2 && !isNumber((*l)[0]);
}

// A key that becomes an element's name must be one (ASCII letters, digits, '_', '-', '.', not
// starting with a digit, '-' or '.'): an empty key or "<a>" would write text the reader
// cannot parse, or take a sibling's attributes.
void checkElementName(const std::string& tag, const std::string& path) {
  auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  bool ok = !tag.empty() && letter(tag[0]);
  for (char c : tag) ok = ok && (letter(c) || (c >= '0' && c <= '9') || c == '-' || c == '.');
  if (!ok)
    throw Error(path + ": expected a parameter name (letters, digits and _), found " +
                (tag.size() > 40 ? "'" + tag.substr(0, 40) + "...'" : "'" + tag + "'"));
}

class TreeWriter {
public:
  SceneTreeText result;

  void root(const SceneTree& t) {
    const Dict* d = t.as<Dict>();
    if (!d)
      throw Error("scene: expected a dictionary of settings, camera, objects, ..., found " +
                  describe(t));
    line("<scene>", "scene");
    for (const auto& [key, v] : *d) {
      if (v.as<std::monostate>()) continue;
      if (key == "settings" || key == "camera")
        element(key, v, key, attributesOf(key));
      else if (key == "objects")
        eachItem(v, key, [&](const SceneTree& o, const std::string& path) { object(o, path); });
      else if (key == "lights")
        eachItem(v, key, [&](const SceneTree& l, const std::string& path) {
          element("light", l, path, attributesOf("light"));
        });
      else if (key == "materials")
        namedItems(v, key, "id", "material");
      else if (key == "spectra")
        namedItems(v, key, "name", "spectrum");
      else
        throw Error(key +
                    ": expected one of the sections settings, camera, objects, lights, "
                    "materials, spectra, found '" +
                    key + "'");
    }
    line("</scene>", "scene");
  }

  void item(const SceneTree& t, bool light, const std::string& path) {
    line("<scene>", path);
    if (light)
      element("light", t, path, attributesOf("light"));
    else
      object(t, path);
    line("</scene>", path);
  }

private:
  void line(const std::string& text, const std::string& path) {
    result.text += text;
    result.text += '\n';
    result.linePaths.push_back(path);
  }

  template <typename F>
  void eachItem(const SceneTree& v, const std::string& key, F f) {
    const List* l = v.as<List>();
    if (!l) throw Error(key + ": expected a list, found " + describe(v));
    for (size_t i = 0; i < l->size(); ++i) f((*l)[i], key + "[" + std::to_string(i) + "]");
  }

  // A section of named items: a list of dictionaries with `nameKey`, or a dictionary of them
  // by name (a spectrum's value may be given directly).
  void namedItems(const SceneTree& v, const std::string& key, const char* nameKey,
                  const std::string& tag) {
    if (const Dict* d = v.as<Dict>()) {
      for (const auto& [name, item] : *d) {
        Dict withName{{nameKey, name}};
        if (const Dict* fields = item.as<Dict>())
          withName.insert(withName.end(), fields->begin(), fields->end());
        else
          withName.emplace_back("value", item);
        element(tag, withName, key + "['" + name + "']", attributesOf(tag));
      }
      return;
    }
    eachItem(v, key, [&](const SceneTree& item, const std::string& path) {
      element(tag, item, path, attributesOf(tag));
    });
  }

  void object(const SceneTree& o, const std::string& path) {
    const Dict* d = o.as<Dict>();
    if (!d) throw Error(path + ": expected a dictionary with a \"shape\", found " + describe(o));
    const SceneTree* shape = o.find("shape");
    const std::string* tag = shape ? shape->as<std::string>() : nullptr;
    if (!tag)
      throw Error(path + ": expected a \"shape\" (sphere, plane, mesh, ...), found " +
                  (shape ? describe(*shape) : std::string("none")));
    Dict rest;
    for (const auto& [k, v] : *d)
      if (k != "shape") rest.emplace_back(k, v);
    element(*tag, rest, path, kObjectAttributes);
  }

  // A scalar's text; a string "csv:FILE[#COLUMN]" or "texture:FILE" (Python's spectrum forms)
  // becomes attributes instead.
  std::string scalarText(const SceneTree& v, const std::string& path, std::string& attributes) {
    if (const bool* b = v.as<bool>()) return *b ? "true" : "false";
    if (const std::string* s = v.as<std::string>()) {
      if (s->rfind("csv:", 0) == 0 && s->size() > 4) {
        const size_t hash = s->find('#', 4);
        attributes += " csv=\"" + escaped(s->substr(4, hash - 4)) + "\"";
        if (hash != std::string::npos)
          attributes += " column=\"" + escaped(s->substr(hash + 1)) + "\"";
        return "";
      }
      if (s->rfind("texture:", 0) == 0 && s->size() > 8) {
        attributes += " texture=\"" + escaped(s->substr(8)) + "\"";
        return "";
      }
      return escaped(*s);
    }
    if (isPairs(v)) {
      std::vector<std::string> nm, value;
      flatten((*v.as<List>())[0], nm), flatten((*v.as<List>())[1], value);
      std::string out;
      for (size_t i = 0; i < nm.size(); ++i) out += (i ? ", " : "") + nm[i] + ":" + value[i];
      return out;
    }
    if (isNumeric(v)) return numbersText(v);
    throw Error(path + ": expected a number, a string, numbers or (wavelengths, values), found " +
                describe(v));
  }

  std::string attributeText(const SceneTree& v, const std::string& path) {
    if (const std::string* s = v.as<std::string>()) return escaped(*s);
    if (const bool* b = v.as<bool>()) return *b ? "true" : "false";
    if (isNumeric(v)) return numbersText(v);
    throw Error(path + ": expected a number or a string, found " + describe(v));
  }

  // <tag ...> from a value: a dictionary gives attributes (the names `attributes` lists, and
  // the suffixed keys of its children) and child elements ("value": the text); anything else
  // is the element's text.
  void element(const std::string& tag, const SceneTree& v, const std::string& path,
               const Names& attributes) {
    if (v.as<std::monostate>()) return;
    checkElementName(tag, path);
    const std::string indent(2 * depth_, ' ');
    const Dict* d = v.as<Dict>();
    if (!d && tag == "transform" && v.as<List>() && !isNumeric(v)) { // steps in order
      line(indent + "<transform>", path);
      ++depth_;
      eachItem(v, path, [&](const SceneTree& step, const std::string& p) {
        const Dict* s = step.as<Dict>();
        if (!s) throw Error(p + ": expected a step {\"translate\": ...}, found " + describe(step));
        for (const auto& [k, x] : *s) element(k, x, p + "." + k, attributesOf(k));
      });
      --depth_;
      line(indent + "</transform>", path);
      return;
    }
    if (!d && tag == "transform" && isNumeric(v)) { // [m | t] rows, 3 or 4
      std::vector<std::string> n;
      flatten(v, n);
      if (n.size() == 12) n.insert(n.end(), {"0", "0", "0", "1"});
      std::string m;
      for (size_t i = 0; i < n.size(); ++i) m += (i ? " " : "") + n[i];
      line(indent + "<transform><matrix>" + m + "</matrix></transform>", path);
      return;
    }
    std::string attrs;
    if (!d) {
      const std::string text = kRowKeys.count(tag) && isNumeric(v)
                                   ? numbersText(v, kFloatRowKeys.count(tag) > 0)
                                   : scalarText(v, path, attrs);
      line(indent + "<" + tag + attrs + ">" + text + "</" + tag + ">", path);
      return;
    }
    // Which keys are attributes of which child: NAME_<suffix> of a sibling NAME.
    std::set<std::string> keys;
    for (const auto& [k, x] : *d) keys.insert(k);
    // (base, suffix) of a suffixed key, nothing for any other (an empty key included).
    auto suffixOf =
        [&](const std::string& k) -> std::optional<std::pair<std::string, std::string>> {
      for (const char* s : kAttributeSuffixes) {
        const std::string suffix = std::string("_") + s;
        if (k.size() > suffix.size() && k.ends_with(suffix) &&
            keys.count(k.substr(0, k.size() - suffix.size())))
          return std::pair<std::string, std::string>{k.substr(0, k.size() - suffix.size()), s};
      }
      return std::nullopt;
    };
    std::string text;
    std::vector<const std::pair<std::string, SceneTree>*> children;
    for (const auto& entry : *d) {
      const auto& [k, x] = entry;
      if (x.as<std::monostate>()) continue;
      if (attributes.count(k) && !x.as<Dict>())
        attrs += " " + k + "=\"" + attributeText(x, path + "." + k) + "\"";
      else if (k == "value")
        text = scalarText(x, path + "." + k, attrs);
      else if (!suffixOf(k))
        children.push_back(&entry);
    }
    if (children.empty()) {
      line(indent + "<" + tag + attrs + ">" + text + "</" + tag + ">", path);
      return;
    }
    if (!text.empty())
      throw Error(path + ".value: expected no \"value\" beside child elements, found one");
    line(indent + "<" + tag + attrs + ">", path);
    ++depth_;
    for (const auto* entry : children) {
      const auto& [k, x] = *entry;
      // Attributes of this child from its suffixed siblings, as a dictionary.
      Dict withSuffixed;
      for (const auto& [k2, x2] : *d)
        if (const auto bs = suffixOf(k2); bs && bs->first == k && !x2.as<std::monostate>())
          withSuffixed.emplace_back(bs->second, x2);
      if (withSuffixed.empty()) {
        element(k, x, path + "." + k, attributesOf(k));
        continue;
      }
      if (const Dict* xd = x.as<Dict>())
        withSuffixed.insert(withSuffixed.begin(), xd->begin(), xd->end());
      else
        withSuffixed.emplace_back("value", x);
      Names with = attributesOf(k);
      for (const auto& [s, unused] : withSuffixed)
        if (s != "value") with.insert(s);
      element(k, withSuffixed, path + "." + k, with);
    }
    --depth_;
    line(indent + "</" + tag + ">", path);
  }

  int depth_ = 1;
};

} // namespace

SceneTreeText itemTreeText(const SceneTree& item, bool light, const std::string& path) {
  TreeWriter w;
  w.item(item, light, path);
  return std::move(w.result);
}

SceneTreeText sceneTreeText(const SceneTree& root) {
  TreeWriter w;
  w.root(root);
  return std::move(w.result);
}

} // namespace nx
