#include "apps/python/py_readonly.h"

namespace nxpy {
namespace {

// The message of every mutating method.
[[noreturn]] void refuse(const std::string& name, const char* method) {
  throw py::type_error(
      name + "." + method + ": " + name +
      " cannot be changed from Python (the scene's named items are those of its file or dict): "
      "set their parameters (scene.set(name, value), scene.parameters() lists them), or write "
      "the item into the scene's dict or text and read it with nxrender.Scene.from_dict or "
      "from_text");
}

} // namespace

void bindReadOnlyContainers(py::module_& m) {
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
