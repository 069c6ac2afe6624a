#include "apps/python/py_scene_lists.h"

#include <algorithm>

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
  static std::vector<Desc>& items(SceneState& s) { return s.desc.objects; }
  static uint64_t& version(SceneState& s) { return s.objectsVersion; }
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
  static std::vector<Desc>& items(SceneState& s) { return s.desc.lights; }
  static uint64_t& version(SceneState& s) { return s.lightsVersion; }
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

  typename Items::View view(size_t i) const { return {s, i, Items::version(*s)}; }

  // The item a Python value describes, placed at `where`: a view (of any scene) or a dict.
  typename Items::Desc itemOf(const py::handle& value, const std::string& where) const {
    if (py::isinstance<typename Items::View>(value)) {
      typename Items::Desc d = value.cast<const typename Items::View&>().get();
      Items::checkCopy(d, *s, where);
      return d;
    }
    if (!py::isinstance<py::dict>(value))
      throw py::type_error(where + ": expected a dict or an nxrender." +
                           (Items::kLight ? "Light" : "Object") + ", found " + typeName(value));
    const nx::SceneTree tree = treeFromPython(value, where);
    return std::get<typename Items::Desc>(nx::parseItemTree(tree, Items::kLight, where, s->desc));
  }

  void changed(const std::string& edit) const {
    ++Items::version(*s);
    s->edits.push_back(edit);
  }

  void insert(long long at, const py::handle& value) const {
    const size_t i = position(at, true);
    typename Items::Desc d = itemOf(value, label(i));
    items().insert(items().begin() + static_cast<std::ptrdiff_t>(i), std::move(d));
    changed(std::string(Items::kName) + ".insert(" + std::to_string(i) + ", " +
            py::repr(value).cast<std::string>() + ")");
  }

  void assign(long long at, const py::handle& value) const {
    const size_t i = position(at);
    items()[i] = itemOf(value, label(i));
    changed(label(i) + " = " + py::repr(value).cast<std::string>());
  }

  void erase(long long at) const {
    const size_t i = position(at);
    items().erase(items().begin() + static_cast<std::ptrdiff_t>(i));
    changed("del " + label(i));
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
                 "in Scene.edits. Views taken before an insertion or removal refuse to be used.")
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
          "extend",
          [](const L& l, const py::iterable& items) {
            for (const py::handle& v : items) l.insert(static_cast<long long>(l.items().size()), v);
          },
          py::arg("items"), "Adds each item at the end, in order")
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
