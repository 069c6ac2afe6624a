#pragma once
// nxrender.Image: a spectral image (a render, or a file of the Fichet et al. layout) seen from
// numpy; its arrays are views of the image's own storage.

#include <pybind11/pybind11.h>

#include "io/spectral_exr.h"

namespace nxpy {

namespace py = pybind11;

/// The Python object behind nxrender.Image.
struct PyImage {
  nx::SpectralImage image;
};

/// Registers Image, read_exr, write_exr and write_envi.
void bindImage(py::module_& m);

} // namespace nxpy
