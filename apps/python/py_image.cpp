// nxrender.Image, read_exr, write_exr, write_envi.

#include "apps/python/py_image.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cfloat>
#include <cmath>
#include <filesystem>
#include <type_traits>

#include "apps/python/py_arguments.h"
#include "apps/python/py_arrays.h"
#include "core/error.h"
#include "core/hash.h"
#include "integrators/render_scene.h"
#include "io/aov_names.h"
#include "io/envi_export.h"
#include "io/exr_compression.h"
#include "io/spectral_cube.h"
#include "spectra/band_colour.h"

namespace nxpy {
namespace {

// A numpy view (H, W, depth) of a pixel-interleaved vector owned by the image `owner`; None
// when the vector is empty (the image does not hold that channel).
template <typename T>
py::object view(const py::object& owner, std::vector<T>& data, int depth) {
  PyImage& im = owner.cast<PyImage&>();
  if (data.empty()) return py::none();
  const auto h = static_cast<py::ssize_t>(im.image.height),
             w = static_cast<py::ssize_t>(im.image.width), d = static_cast<py::ssize_t>(depth);
  const auto s = static_cast<py::ssize_t>(sizeof(T));
  if (depth == 1)
    return py::array_t<T>(std::vector<py::ssize_t>{h, w}, std::vector<py::ssize_t>{w * s, s},
                          data.data(), owner);
  return py::array_t<T>(std::vector<py::ssize_t>{h, w, d},
                        std::vector<py::ssize_t>{w * d * s, d * s, s}, data.data(), owner);
}

// One array view per component layer of the image owned by `self`, by layer name: its values
// or its variances (`member`).
py::dict layerViews(const py::object& self, std::vector<float> nx::ImageLayer::*member) {
  auto& image = self.cast<PyImage&>().image;
  py::dict out;
  for (nx::ImageLayer& l : image.layers)
    if (l.name.rfind("gradient.", 0) != 0)
      out[py::str(l.name)] = view(self, l.*member, image.bands.count());
  return out;
}

// The ground-truth layers of the image owned by `self` by name, (H, W, channels) views: the
// fluorescence as two, 'fluorescence.absorption' and 'fluorescence.emission' (H, W, bands).
// Image.aovs' docstring: every ground-truth layer's key and shape (NX_AOV_LAYERS).
const char* aovViewsDoc() {
  static const std::string doc = [] {
    std::string s = "dict of ground-truth layer name -> float32 array (aovs=[...], "
                    "docs/datasets.md): ";
    for (size_t i = 0; i < std::size(nx::kAovKinds); ++i) {
      const nx::AovKind k = nx::kAovKinds[i];
      const std::string n = std::string("'") + nx::aovName(k);
      s += i == 0 ? "" : ", ";
      switch (nx::aovLayout(k)) {
      case nx::AovLayout::Vector:
        s += n + "' (H, W, 3, world space)";
        break;
      case nx::AovLayout::Uv:
        s += n + "' (H, W, 2)";
        break;
      case nx::AovLayout::PerBand:
        s += n + "' (H, W, bands)";
        break;
      case nx::AovLayout::AbsorptionEmission:
        s += n + ".absorption' and " + n + ".emission' (H, W, bands)";
        break;
      }
    }
    return s + "; empty without them";
  }();
  return doc.c_str();
}

py::dict aovViews(const py::object& self) {
  auto& image = self.cast<PyImage&>().image;
  py::dict out;
  const auto h = static_cast<py::ssize_t>(image.height), w = static_cast<py::ssize_t>(image.width);
  const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  for (nx::AovImageLayer& l : image.aovs) {
    const auto n = static_cast<py::ssize_t>(l.values.size() / pixels);
    const auto kind = nx::aovKindNamed(l.name);
    if (!kind || nx::aovLayout(*kind) != nx::AovLayout::AbsorptionEmission) {
      out[py::str(l.name)] = view(self, l.values, static_cast<int>(n));
      continue;
    }
    const py::ssize_t nb = n / 2, s = sizeof(float);
    for (const auto& [part, first] : {std::pair{"absorption", 0}, std::pair{"emission", 1}})
      out[py::str(l.name + "." + part)] = py::array_t<float>(
          std::vector<py::ssize_t>{h, w, nb}, std::vector<py::ssize_t>{w * n * s, n * s, s},
          l.values.data() + first * nb, self);
  }
  return out;
}

// A differentiated render's gradients by parameter name (their values or variances): the
// layers "gradient.<slot>", one (H, W, bands) array per number, stacked (n, H, W, bands) for
// a vector parameter.
py::dict gradientViews(const py::object& self, std::vector<float> nx::ImageLayer::*member) {
  auto& p = self.cast<PyImage&>();
  py::dict out;
  const py::object np = py::module_::import("numpy");
  for (const GradientParameter& g : p.gradients) {
    py::list parts;
    for (uint32_t k = g.firstSlot; k < g.firstSlot + g.slots; ++k)
      for (nx::ImageLayer& l : p.image.layers)
        if (l.name == "gradient." + std::to_string(k))
          parts.append(view(self, l.*member, p.image.bands.count()));
    if (static_cast<uint32_t>(py::len(parts)) != g.slots) continue;
    py::object value = g.indexed ? np.attr("stack")(parts) : py::object(parts[0]);
    if (!g.shape.empty()) {
      py::list shape;
      for (long n : g.shape) shape.append(n);
      for (const py::handle n : value.attr("shape")[py::slice(1, 4, 1)]) shape.append(n);
      value = value.attr("reshape")(py::tuple(shape));
    }
    out[py::str(g.name)] = value;
  }
  return out;
}

std::vector<double> centroids(const nx::Sensor& s) {
  std::vector<double> v;
  for (int b = 0; b < s.count(); ++b) v.push_back(s.centroid(b));
  return v;
}

PyImage makeImage(const py::object& radiance, const py::object& wavelengths,
                  const py::object& bands, const py::object& variance,
                  const py::object& sampleCount, const py::object& attributes) {
  const py::array probe = realArray(radiance, "radiance");
  if (probe.ndim() != 3 || probe.shape(0) < 1 || probe.shape(1) < 1 || probe.shape(2) < 1)
    throw py::value_error("radiance: expected a non-empty array of shape (height, width, "
                          "bands), found " +
                          std::to_string(probe.ndim()) + " dimensions");
  PyImage out;
  nx::SpectralImage& im = out.image;
  im.height = static_cast<int>(probe.shape(0));
  im.width = static_cast<int>(probe.shape(1));
  const py::ssize_t nb = probe.shape(2);
  if (wavelengths.is_none() == bands.is_none())
    throw py::value_error("wavelengths, bands: expected one of them (band centres in nm, or a "
                          "description such as '400:700:10')");
  if (!bands.is_none()) {
    im.bands = nx::Sensor::parse(stringArgument(bands, "bands"), "bands");
  } else {
    im.bands =
        nx::sensorAtWavelengths(numberListArgument(wavelengths, "wavelengths", 1), "wavelengths");
  }
  if (im.bands.count() != nb)
    throw py::value_error("radiance: expected " + std::to_string(im.bands.count()) +
                          " bands (one per wavelength), found " + std::to_string(nb));
  im.radiance =
      pixelsArgument<float>(radiance, "radiance", im.height, im.width, nb, -FLT_MAX, FLT_MAX);
  if (!variance.is_none())
    im.bandVariance =
        pixelsArgument<float>(variance, "variance", im.height, im.width, nb, 0, FLT_MAX);
  if (!sampleCount.is_none())
    im.sampleCount = pixelsArgument<uint32_t>(sampleCount, "sample_count", im.height, im.width, 0,
                                              0, 4294967295.0);
  nx::BandColour(centroids(im.bands)).fill(im.radiance, im.xyz, im.rgb);
  if (!attributes.is_none()) {
    if (!py::isinstance<py::dict>(attributes))
      throw py::type_error("attributes: expected a dict of str to str, found " +
                           typeName(attributes));
    for (auto [k, v] : attributes.cast<py::dict>())
      im.attributes[stringArgument(k, "attributes (key)")] = stringArgument(v, "attributes");
  }
  im.attributes["nxrender.bands"] = im.bands.toString();
  return out;
}

} // namespace

std::shared_ptr<const nx::SpectralTexels>
texelsArgument(const py::handle& wavelengths, const py::handle& values, const std::string& param) {
  const py::array a = realArray(values, (param + "[1] (values)").c_str());
  if (a.ndim() != 3 || a.shape(0) < 1 || a.shape(1) < 1 || a.shape(2) < 1)
    throw py::value_error(param + ": expected texel values of shape (height, width, bands)");
  auto t = std::make_shared<nx::SpectralTexels>();
  t->nm = numberListArgument(wavelengths, (param + "[0] (wavelengths)").c_str(), 1);
  if (static_cast<py::ssize_t>(t->nm.size()) != a.shape(2))
    throw py::value_error(param + ": expected one wavelength per band, found " +
                          std::to_string(t->nm.size()) + " wavelengths and " +
                          std::to_string(a.shape(2)) + " bands");
  for (size_t i = 0; i < t->nm.size(); ++i)
    if (!(t->nm[i] > 0 && std::isfinite(t->nm[i])) || (i > 0 && !(t->nm[i] > t->nm[i - 1])))
      throw py::value_error(param + ": expected increasing positive wavelengths");
  if (static_cast<double>(a.size()) * sizeof(float) > static_cast<double>(nx::kMaxTextureFileBytes))
    throw py::value_error(param + ": expected a texture of at most " +
                          std::to_string(nx::kMaxTextureFileBytes >> 20) + " MiB of float32");
  t->height = static_cast<int>(a.shape(0));
  t->width = static_cast<int>(a.shape(1));
  t->values = pixelsArgument<float>(a, (param + "[1] (values)").c_str(), a.shape(0), a.shape(1),
                                    a.shape(2), 0.0, 1.0);
  t->digest = nx::spectralTexelsDigest(*t);
  return t;
}

py::object texelsToPython(const nx::SpectralTexels& t) {
  py::array_t<float> values({static_cast<py::ssize_t>(t.height), static_cast<py::ssize_t>(t.width),
                             static_cast<py::ssize_t>(t.nm.size())});
  std::copy(t.values.begin(), t.values.end(), values.mutable_data());
  return py::make_tuple(py::cast(t.nm), values);
}

namespace {

// nxrender.Image: its arrays, colour, counts and provenance.
void bindImageClass(py::module_& m) {
  py::class_<PyImage>(m, "Image",
                      "A spectral image: band radiances with their error estimates, colour, "
                      "sample counts and provenance. Array properties are numpy views of the "
                      "image (writable; they live as long as the image).")
      .def(py::init(&makeImage), py::arg("radiance"), py::arg("wavelengths") = py::none(),
           py::arg("bands") = py::none(), py::arg("variance") = py::none(),
           py::arg("sample_count") = py::none(), py::arg("attributes") = py::none(),
           "An image from arrays: radiance (H, W, bands) with the bands' centre wavelengths "
           "(nm; evenly spaced -> uniform boxes, else Gaussians as wide as the spacing) or a "
           "band description ('400:700:10', 'gaussian:...'); optional variance (H, W, bands), "
           "sample_count (H, W) and str attributes. XYZ and RGB are computed from the bands.")
      .def_property_readonly(
          "radiance",
          [](py::object self) {
            auto& i = self.cast<PyImage&>().image;
            return view(self, i.radiance, i.bands.count());
          },
          "(H, W, bands) float32: radiance averaged over each band (W m^-2 sr^-1 nm^-1)")
      .def_property_readonly(
          "variance",
          [](py::object self) {
            auto& i = self.cast<PyImage&>().image;
            return view(self, i.bandVariance, i.bands.count());
          },
          "(H, W, bands) float32: variance of each band mean (Monte Carlo error), or None")
      .def_property_readonly(
          "y_variance",
          [](py::object self) {
            auto& i = self.cast<PyImage&>().image;
            return view(self, i.yVariance, 1);
          },
          "(H, W) float32: variance of the mean luminance Y, or None")
      .def_property_readonly(
          "xyz", [](py::object self) { return view(self, self.cast<PyImage&>().image.xyz, 3); },
          "(H, W, 3) float32: CIE 1931 XYZ, or None")
      .def_property_readonly(
          "rgb", [](py::object self) { return view(self, self.cast<PyImage&>().image.rgb, 3); },
          "(H, W, 3) float32: linear sRGB (D65), negatives clamped to 0")
      .def_property_readonly(
          "sample_count",
          [](py::object self) { return view(self, self.cast<PyImage&>().image.sampleCount, 1); },
          "(H, W) uint32: samples behind each pixel, or None")
      .def_property_readonly(
          "white",
          [](py::object self) {
            auto& i = self.cast<PyImage&>().image;
            return view(self, i.white, i.bands.count());
          },
          "(H, W, bands) float32: white reference (aovs=['white']), or None")
      .def_property_readonly(
          "components", [](py::object self) { return layerViews(self, &nx::ImageLayer::values); },
          "dict of component layer name ('reflected', 'fluoresced', 'direct', 'indirect', "
          "'light.NAME') -> (H, W, bands) float32 (aovs=['components', 'lightgroups']); empty "
          "without them")
      .def_property_readonly(
          "gradients", [](py::object self) { return gradientViews(self, &nx::ImageLayer::values); },
          "dict parameter name -> d radiance / d parameter, (H, W, bands) float32, or "
          "(components, H, W, bands) for a spectrum's values or a colour "
          "(render(gradients=[...]), docs/inverse.md); empty otherwise")
      .def_property_readonly(
          "gradient_variances",
          [](py::object self) { return gradientViews(self, &nx::ImageLayer::variances); },
          "dict parameter name -> the variance of each gradient's estimate, shaped as it")
      .def_property_readonly(
          "component_variances",
          [](py::object self) { return layerViews(self, &nx::ImageLayer::variances); },
          "dict of component layer name -> (H, W, bands) float32 variance of its means")
      .def_property_readonly(
          "aovs", [](py::object self) { return aovViews(self); }, aovViewsDoc())
      .def_property_readonly(
          "object_id",
          [](py::object self) { return view(self, self.cast<PyImage&>().image.objectId, 1); },
          "(H, W) uint32: object at each pixel centre, 0 for none (aovs=['ids']), or None")
      .def_property_readonly(
          "material_id",
          [](py::object self) { return view(self, self.cast<PyImage&>().image.materialId, 1); },
          "(H, W) uint32: its material (aovs=['ids']), or None")
      .def_property_readonly(
          "depth", [](py::object self) { return view(self, self.cast<PyImage&>().image.depth, 1); },
          "(H, W) float32: camera-space depth at each pixel centre (aovs=['depth']), or None")
      .def_property_readonly(
          "wavelengths",
          [](const PyImage& p) { return py::array_t<double>(py::cast(centroids(p.image.bands))); },
          "(bands,) float64: each band's centroid in nm (its channel name)")
      .def_property_readonly(
          "fwhm",
          [](const PyImage& p) {
            std::vector<double> v;
            for (int b = 0; b < p.image.bands.count(); ++b) v.push_back(p.image.bands.fwhm(b));
            return py::array_t<double>(py::cast(v));
          },
          "(bands,) float64: each band's full width at half maximum in nm")
      .def_property_readonly(
          "band_names",
          [](const PyImage& p) {
            std::vector<std::string> v;
            for (int b = 0; b < p.image.bands.count(); ++b)
              v.push_back(p.image.bands.channel(b).name);
            return v;
          },
          "Each band's own name (a measured sensor's band list, e.g. '650'; else generated)")
      .def_property_readonly(
          "channel_wavelengths",
          [](const PyImage& p) {
            std::vector<double> v;
            for (int b = 0; b < p.image.bands.count(); ++b) v.push_back(p.image.bands.channelNm(b));
            return py::array_t<double>(py::cast(v));
          },
          "(bands,) float64: the wavelengths naming the EXR channels (a measured band's nominal "
          "centre, else its centroid)")
      .def_property_readonly(
          "bands", [](const PyImage& p) { return p.image.bands.toString(); },
          "The bands as nxrender describes them ('400:700:10', 'gaussian:...', 'table:...')")
      .def_property(
          "attributes", [](const PyImage& p) { return p.image.attributes; },
          [](PyImage& p, const py::dict& d) {
            std::map<std::string, std::string> a;
            for (auto [k, v] : d)
              a[stringArgument(k, "attributes (key)")] = stringArgument(v, "attributes");
            p.image.attributes = std::move(a);
          },
          "Provenance as a dict of str (a copy; assign a dict to replace it)")
      .def_property_readonly("width", [](const PyImage& p) { return p.image.width; })
      .def_property_readonly("height", [](const PyImage& p) { return p.image.height; })
      .def_property_readonly(
          "origin",
          [](const PyImage& p) { return py::make_tuple(p.image.originX, p.image.originY); },
          "(x, y) of the stored region's top-left pixel in the full image (crops)")
      .def_property_readonly(
          "full_size",
          [](const PyImage& p) {
            return py::make_tuple(p.image.displayWidth(), p.image.displayHeight());
          },
          "(width, height) of the full image")
      .def("__repr__", [](const PyImage& p) {
        return "<nxrender.Image " + std::to_string(p.image.width) + "x" +
               std::to_string(p.image.height) + ", " + p.image.bands.summary() + ">";
      });
}

// The image files: read_exr and the writers.
void bindImageFiles(py::module_& m) {
  m.def(
      "read_exr",
      [](const py::object& path) {
        const std::string p = pathArgument(path, "path");
        std::error_code ec;
        if (!std::filesystem::exists(p, ec)) {
          PyErr_SetString(PyExc_FileNotFoundError, (p + ": no such file").c_str());
          throw py::error_already_set();
        }
        PyImage out;
        {
          py::gil_scoped_release release;
          out.image = nx::readSpectralExr(p);
        }
        return out;
      },
      py::arg("path"),
      "Reads a spectral OpenEXR: nxrender's own, or any file of the Fichet et al. 2021 layout "
      "(S0 or T channels in any unit).");
  m.def(
      "read_cube",
      [](const py::object& path, const py::object& wavelengths, const py::object& fwhm) {
        const std::string p = pathArgument(path, "path");
        std::error_code ec;
        if (!std::filesystem::exists(p, ec)) {
          PyErr_SetString(PyExc_FileNotFoundError, (p + ": no such file").c_str());
          throw py::error_already_set();
        }
        nx::CubeReadOptions options;
        if (!wavelengths.is_none())
          options.wavelengthNm = numberListArgument(wavelengths, "wavelengths", 1);
        if (!fwhm.is_none())
          options.fwhmNm = py::isinstance<py::float_>(fwhm) || py::isinstance<py::int_>(fwhm)
                               ? std::vector<double>{numberArgument(fwhm, "fwhm", 1e-9, 1e9)}
                               : numberListArgument(fwhm, "fwhm", 1);
        nx::SpectralCube cube;
        {
          py::gil_scoped_release release;
          cube = nx::readSpectralCube(p, options);
        }
        PyImage out;
        nx::SpectralImage& im = out.image;
        im.width = cube.width;
        im.height = cube.height;
        im.bands = cube.fwhmNm.empty() ? nx::sensorAtWavelengths(cube.wavelengthNm, p)
                                       : nx::Sensor::gaussian(cube.wavelengthNm, cube.fwhmNm, p);
        im.radiance = std::move(cube.values);
        im.bandVariance = std::move(cube.variance);
        im.objectId = std::move(cube.objectId);
        nx::BandColour(centroids(im.bands)).fill(im.radiance, im.xyz, im.rgb);
        im.attributes["nxrender.cubeFormat"] = cube.format;
        im.sourceFiles = {p}; // no writer replaces it with this image
        im.attributes["nxrender.bands"] = im.bands.toString();
        return out;
      },
      py::arg("path"), py::arg("wavelengths") = py::none(), py::arg("fwhm") = py::none(),
      "Reads a capture as nxcompare does: an ENVI cube (.hdr or its data file), a multi-band "
      "TIFF, a directory of per-band PNGs, or a spectral EXR; `wavelengths` (nm) and `fwhm` "
      "(one value or one per band) for files that do not give them. Bands with a FWHM are "
      "Gaussians; values as stored (no scaling).");
  m.def(
      "write_exr",
      [](const py::object& path, const PyImage& image, bool half, const py::object& compression,
         const py::object& zipLevel) {
        const std::string p = pathArgument(path, "path");
        nx::ExrEncoding encoding;
        try {
          if (!compression.is_none())
            encoding.compression =
                nx::parseExrCompression(stringArgument(compression, "compression"), "compression");
        } catch (const nx::Error& e) {
          throw py::value_error(e.what());
        }
        if (!zipLevel.is_none())
          encoding.zipLevel = static_cast<int>(numberArgument(zipLevel, "zip_level", 1, 9));
        py::gil_scoped_release release;
        if (half)
          nx::writeSpectralExrHalf(p, image.image, encoding);
        else
          nx::writeSpectralExr(p, image.image, encoding);
      },
      py::arg("path"), py::arg("image"), py::arg("half") = false,
      py::arg("compression") = py::none(), py::arg("zip_level") = py::none(),
      "Writes an Image as a spectral OpenEXR (Fichet et al. 2021 layout; the file appears "
      "complete or not at all). half=True stores half floats (error if a value does not fit). "
      "compression: as nxrender's --compression ('none', the default for floats; 'piz', the "
      "default for half; 'zip', 'zips', 'rle', or the lossy 'pxr24', 'b44', 'b44a', 'dwaa', "
      "'dwab'); zip_level 1-9 for zip and zips (default 4).");
  m.def(
      "write_envi",
      [](const py::object& path, const PyImage& image) {
        const std::string p = pathArgument(path, "path");
        py::gil_scoped_release release;
        nx::writeEnvi(p, image.image);
        return nx::enviHeaderPath(p);
      },
      py::arg("path"), py::arg("image"),
      "Writes the bands as an ENVI cube: the data file `path` (BSQ float32) and its .hdr "
      "(wavelength, fwhm); returns the header's path.");
}

} // namespace

void bindImage(py::module_& m) {
  bindImageClass(m);
  bindImageFiles(m);
}

} // namespace nxpy
