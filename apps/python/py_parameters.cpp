#include "apps/python/py_parameters.h"

#include "core/error.h"

#include <pybind11/stl.h>

#include "apps/python/py_arguments.h"
#include "apps/python/py_arrays.h"
#include "apps/python/py_image.h"
#include "core/params/array_values.h"

#include <pybind11/numpy.h>

#include <cmath>
#include <limits>

namespace nxpy {

double rangedArgument(const py::handle& value, const std::string& param,
                      const nx::ParameterRange& r) {
  const double v = numberArgument(value, param.c_str(), -1e300, 1e300);
  if (!r.contains(v))
    throw py::value_error(param + ": expected " + r.what + " in " + (r.openLow ? "(" : "[") +
                          py::str(py::float_(r.lo)).cast<std::string>() + ", " +
                          py::str(py::float_(r.hi)).cast<std::string>() + "], found " +
                          py::str(py::float_(v)).cast<std::string>());
  return v;
}

py::object spectrumToPython(const nx::SpectrumDesc& s) {
  switch (s.kind) {
  case nx::SpectrumDesc::Kind::Number:
    return py::float_(s.number);
  case nx::SpectrumDesc::Kind::Name:
    return py::str(s.name);
  case nx::SpectrumDesc::Kind::Pairs:
    return py::make_tuple(py::cast(s.nm), py::cast(s.value));
  case nx::SpectrumDesc::Kind::CsvFile:
    return py::str("csv:" + s.path + (s.column.empty() ? "" : "#" + s.column));
  case nx::SpectrumDesc::Kind::Texture:
    if (s.texels) return texelsToPython(*s.texels);
    return py::str("texture:" + s.texture);
  }
  return py::none();
}

nx::SpectrumDesc spectrumFromPython(const py::handle& value, const std::string& param,
                                    const nx::SourceLocation& loc) {
  nx::SpectrumDesc s;
  s.loc = loc;
  if (py::isinstance<py::str>(value)) {
    const std::string text = value.cast<std::string>();
    // "csv:FILE[#COLUMN]" and "texture:FILE" (what reading such a parameter gives): files
    // relative to the working directory.
    if (text.rfind("csv:", 0) == 0 && text.size() > 4) {
      s.kind = nx::SpectrumDesc::Kind::CsvFile;
      const size_t hash = text.find('#', 4);
      s.path = text.substr(4, hash == std::string::npos ? std::string::npos : hash - 4);
      if (hash != std::string::npos) s.column = text.substr(hash + 1);
      return s;
    }
    if (text.rfind("texture:", 0) == 0 && text.size() > 8) {
      s.kind = nx::SpectrumDesc::Kind::Texture;
      s.texture = text.substr(8);
      return s;
    }
    s.kind = nx::SpectrumDesc::Kind::Name;
    s.name = text;
    if (s.name.empty()) throw py::value_error(param + ": expected a spectrum name, found ''");
    return s;
  }
  if (py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) {
    if (py::len(value) != 2)
      throw py::value_error(param + ": expected (wavelengths_nm, values), found a sequence of " +
                            std::to_string(py::len(value)));
    // Values of shape (height, width, bands): a texture given as numbers.
    const py::object values = value[py::int_(1)];
    if (py::hasattr(values, "ndim") && values.attr("ndim").cast<int>() == 3) {
      s.kind = nx::SpectrumDesc::Kind::Texture;
      s.texels = texelsArgument(value[py::int_(0)], values, param);
      return s;
    }
    s.kind = nx::SpectrumDesc::Kind::Pairs;
    s.nm = numberListArgument(value[py::int_(0)], (param + "[0] (wavelengths)").c_str(), 2);
    s.value = numberListArgument(value[py::int_(1)], (param + "[1] (values)").c_str(), 2);
    if (s.nm.size() != s.value.size())
      throw py::value_error(param + ": expected as many values as wavelengths, found " +
                            std::to_string(s.value.size()) + " and " + std::to_string(s.nm.size()));
    for (size_t i = 1; i < s.nm.size(); ++i)
      if (!(s.nm[i] > s.nm[i - 1]))
        throw py::value_error(param + ": expected increasing wavelengths");
    return s;
  }
  s.kind = nx::SpectrumDesc::Kind::Number;
  s.number = numberArgument(value, param.c_str(), 0, 1e300);
  return s;
}

namespace {

py::object iorToPython(const nx::IorDesc& i) {
  switch (i.kind) {
  case nx::IorDesc::Kind::Number:
    return py::float_(i.value);
  case nx::IorDesc::Kind::Named:
    return py::str(i.name);
  case nx::IorDesc::Kind::Cauchy:
    return py::make_tuple("cauchy", py::cast(i.coefficients));
  case nx::IorDesc::Kind::Sellmeier:
    return py::make_tuple("sellmeier", py::cast(i.coefficients));
  }
  return py::none();
}

nx::IorDesc iorFromPython(const py::handle& value, const std::string& param,
                          const nx::SourceLocation& loc) {
  nx::IorDesc d;
  d.loc = loc;
  if (py::isinstance<py::str>(value)) {
    d.kind = nx::IorDesc::Kind::Named;
    d.name = value.cast<std::string>();
    if (d.name != "bk7" && d.name != "diamond" && d.name != "fused_silica")
      throw py::value_error(
          param + ": expected a named glass bk7, diamond or fused_silica, found '" + d.name + "'");
    return d;
  }
  if (py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) {
    if (py::len(value) != 2 || !py::isinstance<py::str>(value[py::int_(0)]))
      throw py::value_error(param + ": expected a number, a glass name, (\"cauchy\", [A, B, C]) or "
                                    "(\"sellmeier\", [B1, B2, B3, C1, C2, C3])");
    const std::string formula = value[py::int_(0)].cast<std::string>();
    d.coefficients = numberListArgument(value[py::int_(1)], (param + "[1]").c_str(), 2);
    if (formula == "cauchy" && d.coefficients.size() <= 3) {
      d.kind = nx::IorDesc::Kind::Cauchy;
    } else if (formula == "sellmeier" && d.coefficients.size() == 6) {
      d.kind = nx::IorDesc::Kind::Sellmeier;
    } else {
      throw py::value_error(param +
                            ": expected (\"cauchy\", 2 or 3 coefficients) or (\"sellmeier\", 6 "
                            "coefficients), found ('" +
                            formula + "', " + std::to_string(d.coefficients.size()) + ")");
    }
    return d;
  }
  d.kind = nx::IorDesc::Kind::Number;
  d.value = rangedArgument(value, param, nx::kIorRange);
  return d;
}

} // namespace

nx::ArrayDesc arrayFromPython(const py::handle& value, bool indices, uint32_t columns,
                              const std::string& param) {
  const py::array a = realArray(value, param.c_str());
  if (a.ndim() != 2 || a.shape(1) != static_cast<py::ssize_t>(columns) || a.shape(0) < 1)
    throw py::value_error(param + ": expected an array of shape (N, " + std::to_string(columns) +
                          "), found shape " + py::str(a.attr("shape")).cast<std::string>());
  const auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  const double* x = d.data();
  const size_t n = static_cast<size_t>(d.size());
  auto where = [&](size_t i) {
    return " at [" + std::to_string(i / columns) + ", " + std::to_string(i % columns) + "]";
  };
  try {
    if (indices) {
      std::vector<uint32_t> v(n);
      for (size_t i = 0; i < n; ++i) {
        if (!(x[i] >= 0 && x[i] < 4294967296.0 && x[i] == std::floor(x[i])))
          throw py::value_error(param + ": expected whole numbers in [0, 2^32), found " +
                                py::str(py::float_(x[i])).cast<std::string>() + where(i));
        v[i] = static_cast<uint32_t>(x[i]);
      }
      return nx::indexRows(std::move(v), columns);
    }
    std::vector<float> v(n);
    for (size_t i = 0; i < n; ++i) {
      if (!(std::abs(x[i]) <= std::numeric_limits<float>::max()))
        throw py::value_error(param + ": expected finite numbers that fit a float, found " +
                              py::str(py::float_(x[i])).cast<std::string>() + where(i));
      v[i] = static_cast<float>(x[i]);
    }
    return nx::realRows(std::move(v), columns);
  } catch (const nx::Error& e) {
    throw py::value_error(param + ": " + e.what());
  }
}

py::object parameterToPython(const nx::ParamValue& v) {
  if (const double* d = std::get_if<double>(&v)) return py::float_(*d);
  if (const auto* c = std::get_if<std::array<double, 4>>(&v))
    return py::make_tuple((*c)[0], (*c)[1], (*c)[2], (*c)[3]);
  if (const auto* s = std::get_if<nx::SpectrumDesc>(&v)) return spectrumToPython(*s);
  if (const auto* i = std::get_if<nx::IorDesc>(&v)) return iorToPython(*i);
  if (const auto* c = std::get_if<nx::CoatingDesc>(&v))
    return py::make_tuple(c->thicknessNm, iorToPython(c->ior));
  if (const auto* t = std::get_if<std::string>(&v)) return py::str(*t);
  if (const auto* p = std::get_if<nx::Vec3d>(&v)) return py::make_tuple(p->x, p->y, p->z);
  if (const auto* r = std::get_if<nx::ArrayDesc>(&v)) {
    const py::ssize_t rows = static_cast<py::ssize_t>(r->rows()), cols = r->columns;
    if (r->reals) return py::array_t<float>({rows, cols}, r->reals->data());
    return py::array_t<uint32_t>({rows, cols}, r->indices->data());
  }
  if (const auto* a = std::get_if<nx::AffineDesc>(&v)) {
    py::list rows;
    for (int i = 0; i < 3; ++i)
      rows.append(py::make_tuple(a->m[i][0], a->m[i][1], a->m[i][2], a->t[i]));
    return py::tuple(rows);
  }
  return py::none(); // fluorescence: its own view (py_scene.cpp)
}

nx::ParamValue parameterFromPython(const nx::ParamSpec& spec, const py::handle& value,
                                   const std::string& param, const nx::SourceLocation& loc) {
  switch (spec.type) {
  case nx::ParamType::Number:
    return rangedArgument(value, param, *spec.range);
  case nx::ParamType::Rgb: {
    const std::vector<double> c = numberListArgument(value, param.c_str(), 3);
    if (c.size() > 4)
      throw py::value_error(param + ": expected (r, g, b[, a]), found " + std::to_string(c.size()) +
                            " numbers");
    const double hi = spec.range ? spec.range->hi : 1e12;
    for (size_t i = 0; i < 3; ++i)
      if (!(c[i] >= 0 && c[i] <= hi))
        throw py::value_error(param + (spec.range
                                           ? ": expected reflectance colour channels in [0, 1]"
                                           : ": expected non-negative colour channels"));
    return std::array<double, 4>{c[0], c[1], c[2], c.size() == 4 ? c[3] : 1.0};
  }
  case nx::ParamType::Spectrum: {
    nx::SpectrumDesc d = spectrumFromPython(value, param, loc);
    if (d.kind == nx::SpectrumDesc::Kind::Texture)
      throw py::value_error(param + ": expected a spectrum, found a texture (only <reflectance> "
                                    "takes one)");
    return d;
  }
  case nx::ParamType::Reflectance:
    return spectrumFromPython(value, param, loc);
  case nx::ParamType::Ior:
    return iorFromPython(value, param, loc);
  case nx::ParamType::Coating: {
    if (!(py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) ||
        py::len(value) != 2)
      throw py::type_error(param + ": expected (thickness_nm, ior), found " + typeName(value));
    nx::CoatingDesc c;
    c.loc = loc;
    c.thicknessNm = rangedArgument(value[py::int_(0)], param + "[0]", *spec.range);
    c.ior = iorFromPython(value[py::int_(1)], param + "[1]", loc);
    return c;
  }
  case nx::ParamType::Name:
    return stringArgument(value, param.c_str());
  case nx::ParamType::File:
    return pathArgument(value, param.c_str());
  case nx::ParamType::Point: {
    const std::vector<double> v = numbersArgument(value, param.c_str(), 3);
    for (double x : v)
      if (!(std::abs(x) <= nx::kMaxSceneCoordinate))
        throw py::value_error(param + ": expected coordinates within 1e12, found " +
                              py::str(py::float_(x)).cast<std::string>());
    return nx::Vec3d(v[0], v[1], v[2]);
  }
  case nx::ParamType::Transform: {
    // Rows [m | t] of the affine map: 3 rows, or 4 with the last 0, 0, 0, 1.
    if (!isSequence(value) || (py::len(value) != 3 && py::len(value) != 4))
      throw py::type_error(param +
                           ": expected 3 or 4 rows of 4 numbers (the matrix [m | t]), found " +
                           typeName(value));
    nx::AffineDesc a;
    double t[3] = {0, 0, 0};
    for (size_t i = 0; i < py::len(value); ++i) {
      const std::string row = param + "[" + std::to_string(i) + "]";
      const std::vector<double> r = numbersArgument(value[py::int_(i)], row.c_str(), 4);
      if (i == 3) {
        if (r[0] != 0 || r[1] != 0 || r[2] != 0 || r[3] != 1)
          throw py::value_error(param + ": expected an affine matrix (last row 0, 0, 0, 1)");
        continue;
      }
      for (int j = 0; j < 3; ++j) a.m[i][j] = r[j];
      t[i] = r[3];
    }
    a.t = nx::Vec3d(t[0], t[1], t[2]);
    for (const auto& row : a.m)
      for (double x : row)
        if (!std::isfinite(x) || !std::isfinite(t[0] + t[1] + t[2]))
          throw py::value_error(param + ": expected finite numbers");
    if (!a.keepsVolume())
      throw py::value_error(param +
                            ": expected a transform that keeps volume (non-zero "
                            "determinant), found determinant " +
                            nx::numberText(a.determinant()));
    return a;
  }
  case nx::ParamType::Reals:
  case nx::ParamType::Indices:
    return arrayFromPython(value, spec.type == nx::ParamType::Indices, spec.columns, param);
  case nx::ParamType::Fluorescence:
    throw py::type_error(param + ": set with set_fluorescence(...) or by its fields");
  case nx::ParamType::Dye:
    throw py::type_error(param + ": set with set_dye(...) or by its fields");
  }
  throw py::type_error(param + ": a parameter type without a Python form");
}

} // namespace nxpy
