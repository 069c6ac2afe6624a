#pragma once
// nxrender.Image: a spectral image (a render, or a file of the Fichet et al. layout) seen from
// numpy; its arrays are views of the image's own storage.

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "core/params/scene_values.h"
#include "integrators/gradients/gradient_setup.h"
#include "io/spectral_exr.h"

namespace nxpy {

namespace py = pybind11;

/// A parameter of a differentiated render: its name and its slots.
using GradientParameter = nx::GradientParameter;

/// The Python object behind nxrender.Image.
struct PyImage {
  nx::SpectralImage image;
  /// A differentiated render's parameters: their slots are the layers "gradient.<slot>".
  std::vector<GradientParameter> gradients;
};

/// A reflectance texture given as numbers: values of shape (height, width, bands), each a
/// finite reflectance in [0, 1], at `wavelengths` (increasing nm, one per band); checked (the
/// first offending texel named) and its content digested. `param` names it in errors.
std::shared_ptr<const nx::SpectralTexels>
texelsArgument(const py::handle& wavelengths, const py::handle& values, const std::string& param);

/// A texture's numbers as (wavelengths_nm, values[height, width, bands] float32).
py::object texelsToPython(const nx::SpectralTexels& t);

/// Registers Image, read_exr, write_exr and write_envi.
void bindImage(py::module_& m);

} // namespace nxpy
