// Image.relight and Image.relight_groups (docs/relighting.md).

#include "apps/python/py_relight.h"

#include <pybind11/stl.h>

#include "apps/python/py_arguments.h"
#include "apps/python/py_image.h"
#include "core/error.h"
#include "integrators/relight_image.h"

namespace nxpy {
namespace {

// The new spectrum of `group` from a Python value: a CSV file name (two columns nm,value) or a
// built-in emission name ("D65"), a pair (wavelengths, values) of a piecewise-linear table, or
// one number (flat).
nx::GroupSpectrum spectrumArgument(const nx::SpectralImage& image, const std::string& group,
                                   const py::handle& value, std::vector<std::string>& warnings) {
  const std::string param = "lights['" + group + "']";
  if (py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__"))
    return nx::groupSpectrumFromText(image, group, pathArgument(value, param.c_str()), warnings);
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
    const double v = numberArgument(value, param.c_str(), 0, 1e12);
    return nx::groupSpectrum(image, group, nx::Spectrum(nx::ConstantSpectrum{v}), 0, 1e9, param,
                             warnings);
  }
  if (!py::isinstance<py::tuple>(value) || py::len(value) != 2)
    throw py::type_error(param + ": expected a CSV file name, (wavelengths, values) or a number");
  const py::tuple t = value.cast<py::tuple>();
  std::vector<double> nm = numberListArgument(t[0], (param + "[0]").c_str(), 2);
  std::vector<double> v = numberListArgument(t[1], (param + "[1]").c_str(), 2);
  if (v.size() != nm.size())
    throw py::value_error(param + ": expected as many values as wavelengths, found " +
                          std::to_string(v.size()) + " and " + std::to_string(nm.size()));
  for (size_t i = 0; i < nm.size(); ++i) {
    if (i > 0 && !(nm[i] > nm[i - 1]))
      throw py::value_error(param + "[0]: expected increasing wavelengths, found " +
                            nx::numberText(nm[i]) + " after " + nx::numberText(nm[i - 1]));
    if (!(v[i] >= 0))
      throw py::value_error(param + "[1]: expected values >= 0, found " + nx::numberText(v[i]) +
                            " at " + nx::numberText(nm[i]) + " nm");
  }
  const double lo = nm.front(), hi = nm.back();
  nx::TabulatedSpectrum table;
  table.nm = std::move(nm);
  table.value = std::move(v);
  return nx::groupSpectrum(image, group, nx::Spectrum(std::move(table)), lo, hi, param, warnings);
}

} // namespace

void bindRelight(py::module_& m) {
  auto cls = py::reinterpret_borrow<py::class_<PyImage>>(m.attr("Image"));
  cls.def(
         "relight",
         [](const PyImage& self, const py::dict& lights) {
           std::vector<nx::GroupSpectrum> spectra;
           std::vector<std::string> warnings;
           for (auto [k, v] : lights)
             spectra.push_back(
                 spectrumArgument(self.image, stringArgument(k, "lights (key)"), v, warnings));
           for (const std::string& w : warnings) py::module_::import("warnings").attr("warn")(w);
           PyImage out;
           {
             py::gil_scoped_release release;
             out.image = nx::relightImage(self.image, spectra);
           }
           return out;
         },
         py::arg("lights") = py::dict(),
         "The image under new emission spectra of some light groups: {group: spectrum}, a "
         "spectrum a CSV file (nm,value) or built-in name ('D65'), (wavelengths, values) or a "
         "number; the emitters' "
         "scale= still applies; groups not given keep their rendered spectra. Needs an image "
         "rendered relightable=True (docs/relighting.md). Returns an ordinary Image with "
         "variances.")
      .def_property_readonly(
          "relight_groups", [](const PyImage& self) { return self.image.relight.groups(); },
          "The light groups a relightable image can relight (empty for another image)");
}

} // namespace nxpy
