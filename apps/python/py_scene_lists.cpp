#include "apps/python/py_scene_lists.h"

#include <algorithm>
#include <functional>

#include "apps/python/py_arguments.h"
#include "apps/python/py_scene_tree.h"
#include "integrators/scene_reader.h"
#include "io/scene_to_tree.h"

namespace nxpy {
namespace {

// What differs between the object and the light list.
struct ObjectItems {
  using Desc = nx::ObjectDesc;
  using View = ObjectView;
  static constexpr const char* kName = "objects";
  static constexpr bool kLight = false;
  static constexpr const char* kNoun = "object";
  static std::vector<Desc>& items(SceneState& s) { return s.desc.objects; }
  static ItemRegistry<Desc>& registry(SceneState& s) { return s.objectItems; }
  static nx::SceneTree tree(const Desc& d, const std::string& where) {
    return nx::objectToTree(d, where);
  }
  // An object of another scene may use one of its named materials: this scene must have the
  // same material under the same id.
  static void checkCopy(const Desc& d, const SceneState& s, const std::string& where) {
    if (d.materialRef.empty()) return;
    for (const nx::NamedMaterialDesc& m : s.desc.materials)
      if (m.id == d.materialRef) return;
    throw py::value_error(where + ": expected a material of this scene, found the material '" +
                          d.materialRef + "' of another scene (define it here first)");
  }
};

struct LightItems {
  using Desc = nx::LightDesc;
  using View = LightView;
  static constexpr const char* kName = "lights";
  static constexpr bool kLight = true;
  static constexpr const char* kNoun = "light";
  static std::vector<Desc>& items(SceneState& s) { return s.desc.lights; }
  static ItemRegistry<Desc>& registry(SceneState& s) { return s.lightItems; }
  static nx::SceneTree tree(const Desc& d, const std::string& where) {
    return nx::lightToTree(d, where);
  }
  static void checkCopy(const Desc&, const SceneState&, const std::string&) {}
};

template <class Items>
struct LiveList {
  StatePtr s;

  std::vector<typename Items::Desc>& items() const { return Items::items(*s); }
  std::string label(size_t i) const {
    return std::string(Items::kName) + "[" + std::to_string(i) + "]";
  }

  // Position i of the list (negative from the end); IndexError outside.
  size_t position(long long i, bool forInsert = false) const {
    const long long n = static_cast<long long>(items().size());
    if (forInsert) return static_cast<size_t>(std::clamp(i < 0 ? i + n : i, 0LL, n));
    if (i < -n || i >= n)
      throw py::index_error(std::string(Items::kName) + " index " + std::to_string(i) +
                            " out of range (" + std::to_string(n) + " items)");
    return static_cast<size_t>(i < 0 ? i + n : i);
  }

  typename Items::View view(size_t i) const {
    return {s, Items::registry(*s).at(i, items().size())};
  }

  // The item a Python value describes, placed at `where`: a view (of any scene; an item that
  // left its scene copies as it was) or a dict. Converting may run Python code (a value's
  // __float__, a sequence's __getitem__) that edits this very list: every change below takes
  // its position and references only after all conversions are done.
  typename Items::Desc itemOf(const py::handle& value, const std::string& where) const {
    if (py::isinstance<typename Items::View>(value)) {
      typename Items::Desc d = value.cast<const typename Items::View&>().value();
      Items::checkCopy(d, *s, where);
      return d;
    }
    if (!py::isinstance<py::dict>(value))
      throw py::type_error(where + ": expected a dict or an nxrender." +
                           (Items::kLight ? "Light" : "Object") + ", found " + typeName(value));
    const nx::SceneTree tree = treeFromPython(value, where);
    return std::get<typename Items::Desc>(nx::parseItemTree(tree, Items::kLight, where, s->desc));
  }

  // The label of the item a new one would get at `at` (negative from the end), for messages.
  std::string labelAt(long long at) const { return label(position(at, true)); }

  // Inserts converted items at position `at` (computed now), recorded as `edit(i)`.
  void insertAll(long long at, std::vector<typename Items::Desc> made,
                 const std::function<std::string(size_t)>& edit) const {
    size_t i = position(at, true);
    for (typename Items::Desc& d : made) {
      Items::registry(*s).inserted(i, items().size());
      items().insert(items().begin() + static_cast<std::ptrdiff_t>(i), std::move(d));
      s->edits.push_back(edit(i));
      ++i;
    }
  }

  void insert(long long at, const py::handle& value) const {
    std::vector<typename Items::Desc> made;
    made.push_back(itemOf(value, labelAt(at)));
    const std::string text = py::repr(value).cast<std::string>();
    insertAll(at, std::move(made), [&](size_t i) {
      return std::string(Items::kName) + ".insert(" + std::to_string(i) + ", " + text + ")";
    });
  }

  // All items converted and checked before any is added: a refused one adds none.
  void extend(const py::iterable& values) const {
    std::vector<py::object> given;
    for (const py::handle& v : values) given.push_back(py::reinterpret_borrow<py::object>(v));
    std::vector<typename Items::Desc> made;
    std::vector<std::string> texts;
    const size_t n0 = items().size();
    for (size_t k = 0; k < given.size(); ++k) {
      made.push_back(itemOf(given[k], label(n0 + k)));
      texts.push_back(py::repr(given[k]).cast<std::string>());
    }
    const size_t first = items().size();
    insertAll(static_cast<long long>(first), std::move(made), [&](size_t i) {
      return std::string(Items::kName) + ".insert(" + std::to_string(i) + ", " + texts[i - first] +
             ")";
    });
  }

  void assign(long long at, const py::handle& value) const {
    typename Items::Desc d = itemOf(value, label(position(at)));
    const std::string text = py::repr(value).cast<std::string>();
    const size_t i = position(at); // again: the conversion may have changed the list
    const std::string edit = label(i) + " = " + text;
    Items::registry(*s).leaving(i, items().size(), items()[i], label(i), edit, false);
    items()[i] = std::move(d);
    s->edits.push_back(edit);
  }

  void erase(long long at) const {
    const size_t i = position(at);
    const std::string edit = "del " + label(i);
    Items::registry(*s).leaving(i, items().size(), items()[i], label(i), edit, true);
    items().erase(items().begin() + static_cast<std::ptrdiff_t>(i));
    s->edits.push_back(edit);
  }

  py::object pop(long long at) const {
    const size_t i = position(at);
    py::object removed;
    try {
      removed = treeToPython(Items::tree(items()[i], label(i)));
    } catch (const nx::Error& e) {
      throw py::value_error(std::string(e.what()) + "; remove it with del instead");
    }
    erase(static_cast<long long>(i));
    return removed;
  }
};

template <class Items>
void bindList(py::module_& m, const char* pyName, const char* what) {
  using L = LiveList<Items>;
  py::class_<L>(m, pyName,
                (std::string("The scene's ") + what +
                 " as a live list: append, insert, del, pop and item assignment of a view or a "
                 "dict (Scene.from_dict's form), each checked as a scene file is and recorded "
                 "in Scene.edits. A view follows its item through insertions and removals; once "
                 "the item is removed or replaced, its views read as it was and refuse edits.")
                    .c_str())
      .def("__len__", [](const L& l) { return l.items().size(); })
      .def("__getitem__", [](const L& l, long long i) { return l.view(l.position(i)); })
      .def("__setitem__", &L::assign, py::arg("index"), py::arg("item"))
      .def("__delitem__", &L::erase, py::arg("index"))
      .def("__iter__",
           [](const L& l) {
             py::list views;
             for (size_t i = 0; i < l.items().size(); ++i) views.append(l.view(i));
             return py::iter(views);
           })
      .def(
          "append",
          [](const L& l, const py::handle& v) {
            l.insert(static_cast<long long>(l.items().size()), v);
          },
          py::arg("item"), "Adds an item (a view or a dict) at the end")
      .def(
          "extend", [](const L& l, const py::iterable& items) { l.extend(items); },
          py::arg("items"),
          "Adds each item at the end, in order; all are checked first (a refused one adds none)")
      .def("insert", &L::insert, py::arg("index"), py::arg("item"),
           "Inserts an item (a view or a dict) before position `index`")
      .def("pop", &L::pop, py::arg("index") = -1,
           "Removes the item at `index` and returns it as a dict (Scene.from_dict's form)")
      .def("__repr__", [](const L& l) {
        std::string out = "[";
        for (size_t i = 0; i < l.items().size(); ++i)
          out += (i ? ", " : "") + py::repr(py::cast(l.view(i))).template cast<std::string>();
        return out + "]";
      });
}

} // namespace

void bindSceneLists(py::module_& m) {
  bindList<ObjectItems>(m, "ObjectList", "objects");
  bindList<LightItems>(m, "LightList", "lights");
}

py::object objectList(const StatePtr& s) {
  return py::cast(LiveList<ObjectItems>{s});
}

py::object lightList(const StatePtr& s) {
  return py::cast(LiveList<LightItems>{s});
}

} // namespace nxpy
