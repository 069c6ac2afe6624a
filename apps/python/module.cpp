// The Python module nxrender: render scenes and read/write spectral images from numpy.

#include <pybind11/eval.h>
#include <pybind11/pybind11.h>

#include <filesystem>

#include "accel/geometry_cache.h"
#include "apps/python/py_dataset_codec.h"
#include "apps/python/py_image.h"
#include "apps/python/py_readonly.h"
#include "apps/python/py_relight.h"
#include "apps/python/py_render.h"
#include "apps/python/py_scene.h"
#include "apps/python/py_scene_parameters.h"
#include "core/error.h"
#include "io/mesh_cache.h"

namespace nx {
extern const char* const kTorchBridgePy; // apps/python/nxrender_torch.py
extern const char* const kDatasetPy;     // apps/python/nxrender_dataset.py
} // namespace nx

PYBIND11_MODULE(nxrender, m) {
  m.doc() = "nxrender: spectral path tracing for fluorescence research (docs/python.md)";
  m.attr("__version__") = NX_VERSION;
  // Errors of scene files, data files and images: the command line's messages (file:line).
  pybind11::register_exception<nx::Error>(m, "Error", PyExc_ValueError);
  nxpy::bindImage(m);
  nxpy::bindRelight(m);
  nxpy::bindReadOnlyContainers(m);
  nxpy::bindScene(m);
  nxpy::bindSceneParameters(m);
  nxpy::bindRender(m);
  nxpy::bindDatasetCodec(m);
  m.def(
      "clear_caches",
      [] {
        nx::clearMeshCache();
        nx::clearGeometryCache();
      },
      "Frees the meshes parsed from files and the geometry (BVH) kept for the next render of the "
      "same shapes (both are rebuilt when needed)");
  // nxrender.torch: its Python source compiled in (apps/python/nxrender_torch.py); it imports
  // torch at its first use only.
  pybind11::module_ torch =
      m.def_submodule("torch", "A render as a differentiable PyTorch operation (docs/python.md)");
  pybind11::exec(nx::kTorchBridgePy, torch.attr("__dict__"));
  pybind11::module_::import("sys").attr("modules")["nxrender.torch"] = torch;
  // nxrender.dataset: many scenes rendered into a dataset, read back as a map-style dataset
  // (apps/python/nxrender_dataset.py; nxdataset is its command line).
  pybind11::module_ dataset =
      m.def_submodule("dataset", "Datasets of many scenes (docs/datasets.md)");
  pybind11::exec(nx::kDatasetPy, dataset.attr("__dict__"));
  pybind11::module_::import("sys").attr("modules")["nxrender.dataset"] = dataset;
}
