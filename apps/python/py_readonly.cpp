#include "apps/python/py_readonly.h"

namespace nxpy {
namespace {

// The message of every mutating method.
[[noreturn]] void refuse(const std::string& name, const char* method) {
  throw py::type_error(
      name + "." + method + ": " + name +
      " cannot be changed from Python (the scene's items are those of its file): set their "
      "parameters (scene.set(name, value), scene.parameters() lists them), or write the item into "
      "the scene text and read it with nxrender.Scene.from_text");
}

} // namespace

void bindReadOnlyContainers(py::module_& m) {
  auto list = py::class_<ReadOnlyList>(m, "SceneList",
                                       "A scene's items in file order (read-only: edit their "
                                       "parameters instead)");
  list.def("__len__", [](const ReadOnlyList& l) { return py::len(l.items); })
      .def("__getitem__",
           [](const ReadOnlyList& l, const py::object& i) -> py::object { return l.items[i]; })
      .def("__iter__", [](const ReadOnlyList& l) { return py::iter(l.items); })
      .def("__contains__",
           [](const ReadOnlyList& l, const py::object& o) { return l.items.contains(o); })
      .def("__repr__",
           [](const ReadOnlyList& l) { return std::string(py::repr(py::list(l.items))); })
      .def("__eq__", [](const ReadOnlyList& l, const py::object& o) {
        return py::list(l.items).equal(o) ||
               (py::isinstance<ReadOnlyList>(o) && l.items.equal(o.cast<ReadOnlyList&>().items));
      });
  for (const char* method : {"append", "extend", "insert", "pop", "remove", "clear", "sort",
                             "reverse", "__setitem__", "__delitem__", "__iadd__", "__imul__"})
    list.def(method,
             [method](const ReadOnlyList& l, py::args, py::kwargs) { refuse(l.name, method); });

  auto mapping = py::class_<ReadOnlyMapping>(m, "SceneMapping",
                                             "A scene's named items (read-only: edit their "
                                             "parameters instead)");
  mapping.def("__len__", [](const ReadOnlyMapping& d) { return py::len(d.items); })
      .def("__getitem__",
           [](const ReadOnlyMapping& d, const py::object& k) -> py::object {
             if (!d.items.contains(k))
               throw py::key_error(d.name + " has no item " + std::string(py::repr(k)) +
                                   " (it has " +
                                   std::string(py::repr(py::list(d.items.attr("keys")()))) + ")");
             return d.items[k];
           })
      .def("__iter__", [](const ReadOnlyMapping& d) { return py::iter(d.items); })
      .def("__contains__",
           [](const ReadOnlyMapping& d, const py::object& k) { return d.items.contains(k); })
      .def("keys", [](const ReadOnlyMapping& d) { return d.items.attr("keys")(); })
      .def("values", [](const ReadOnlyMapping& d) { return d.items.attr("values")(); })
      .def("items", [](const ReadOnlyMapping& d) { return d.items.attr("items")(); })
      .def(
          "get",
          [](const ReadOnlyMapping& d, const py::object& k, const py::object& fallback) {
            return d.items.contains(k) ? py::object(d.items[k]) : fallback;
          },
          py::arg("key"), py::arg("default") = py::none())
      .def("__repr__", [](const ReadOnlyMapping& d) { return std::string(py::repr(d.items)); });
  for (const char* method :
       {"__setitem__", "__delitem__", "pop", "popitem", "clear", "update", "setdefault", "__ior__"})
    mapping.def(method, [method](const ReadOnlyMapping& d, py::args, py::kwargs) {
      refuse(d.name, method);
    });
}

} // namespace nxpy
