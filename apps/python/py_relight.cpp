// Image.relight and Image.relight_groups (docs/relighting.md).

#include "apps/python/py_relight.h"

#include <pybind11/stl.h>

#include "apps/python/py_arguments.h"
#include "apps/python/py_image.h"
#include "core/error.h"
#include "integrators/relight_image.h"
#include "integrators/relight_targets.h"

namespace nxpy {

nx::TextSpectrum spectrumFromPython(const py::handle& value, const std::string& param) {
  if (py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__"))
    return nx::spectrumFromText(pathArgument(value, param.c_str()));
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
    const double v = numberArgument(value, param.c_str(), 0, 1e12);
    return {nx::Spectrum(nx::ConstantSpectrum{v}), 0, 1e9};
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
  table.buildIndex();
  return {nx::Spectrum(std::move(table)), lo, hi};
}

std::vector<nx::RelightTargetDesc> relightTargetsArgument(const py::handle& value) {
  std::vector<nx::RelightTargetDesc> out;
  // One spectrum or a list of them, for `group` ("" for every group).
  const auto add = [&](const std::string& group, const py::handle& v, const std::string& param) {
    const bool several = py::isinstance<py::list>(v);
    py::list items = several ? v.cast<py::list>() : py::list();
    if (!several) items.append(v);
    for (size_t i = 0; i < items.size(); ++i) {
      const std::string p = several ? param + "[" + std::to_string(i) + "]" : param;
      nx::RelightTargetDesc t;
      t.group = group;
      t.spectrum = spectrumFromPython(items[i], p).spectrum;
      t.source = py::isinstance<py::str>(items[i]) ? items[i].cast<std::string>() : p;
      t.option = "relight_for";
      t.where = p;
      try {
        nx::checkRelightTarget(t, p);
      } catch (const nx::Error& e) {
        throw py::value_error(e.what());
      }
      out.push_back(std::move(t));
    }
  };
  if (py::isinstance<py::dict>(value)) {
    for (auto [k, v] : value.cast<py::dict>()) {
      const std::string group = stringArgument(k, "relight_for (key)");
      add(group, v, "relight_for['" + group + "']");
    }
  } else {
    add("", value, "relight_for");
  }
  return out;
}

namespace {

// The new spectrum of `group` from a Python value (spectrumFromPython).
nx::GroupSpectrum spectrumArgument(const nx::SpectralImage& image, const std::string& group,
                                   const py::handle& value, std::vector<std::string>& warnings) {
  const std::string param = "lights['" + group + "']";
  if (py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__"))
    return nx::groupSpectrumFromText(image, group, pathArgument(value, param.c_str()), warnings);
  const nx::TextSpectrum t = spectrumFromPython(value, param);
  return nx::groupSpectrum(image, group, t.spectrum, t.loNm, t.hiNm, param, warnings);
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
