#include "apps/python/py_scene_fields.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <climits>

#include "apps/python/py_arguments.h"
#include "apps/python/py_parameters.h"
#include "core/hash.h"
#include "core/params/scene_limits.h"

namespace nxpy {
namespace {

// A measured matrix as Python arrays: (excitation_nm, emission_nm, values[excitation, emission]).
py::object matrixToPython(const nx::MeasuredMatrix& m) {
  py::array_t<double> values({m.excitationNm.size(), m.emissionNm.size()});
  std::copy(m.cells.begin(), m.cells.end(), values.mutable_data());
  return py::make_tuple(py::array_t<double>(m.excitationNm.size(), m.excitationNm.data()),
                        py::array_t<double>(m.emissionNm.size(), m.emissionNm.data()), values);
}

} // namespace

std::shared_ptr<const nx::MeasuredMatrix> matrixFromPython(const py::handle& value,
                                                           const std::string& param) {
  if (!isSequence(value) || py::len(value) != 3)
    throw py::type_error(param + ": expected (excitation_nm, emission_nm, values), found " +
                         typeName(value));
  auto m = std::make_shared<nx::MeasuredMatrix>();
  m->source = param;
  m->excitationNm = numberListArgument(value[py::int_(0)], (param + "[0]").c_str(), 2);
  m->emissionNm = numberListArgument(value[py::int_(1)], (param + "[1]").c_str(), 2);
  const auto cells =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value[py::int_(2)]);
  if (!cells || cells.ndim() != 2)
    throw py::type_error(param + "[2]: expected a 2-d array of values (excitation, emission)");
  if (static_cast<size_t>(cells.shape(0)) != m->excitationNm.size() ||
      static_cast<size_t>(cells.shape(1)) != m->emissionNm.size())
    throw py::value_error(param + "[2]: expected shape (" + std::to_string(m->excitationNm.size()) +
                          ", " + std::to_string(m->emissionNm.size()) + "), found (" +
                          std::to_string(cells.shape(0)) + ", " + std::to_string(cells.shape(1)) +
                          ")");
  m->cells.assign(cells.data(), cells.data() + cells.size());
  return m;
}

std::string matrixEditText(const nx::MeasuredMatrix& m) {
  return "<matrix " + std::to_string(m.excitationNm.size()) + "x" +
         std::to_string(m.emissionNm.size()) + " digest " +
         std::to_string(nx::measuredMatrixDigest(m)) + ">";
}

namespace {

std::shared_ptr<const nx::ConcentrationMap> mapFromPython(const py::handle& value,
                                                          const std::string& param) {
  const py::array_t<double, py::array::c_style | py::array::forcecast> a =
      py::module_::import("numpy").attr("asarray")(value, "float64");
  if (a.ndim() != 2)
    throw py::value_error(param + ": expected values[height, width], found an array of " +
                          std::to_string(a.ndim()) + " axes");
  std::vector<float> values(a.data(), a.data() + a.size());
  return std::make_shared<const nx::ConcentrationMap>(nx::makeConcentrationMap(
      static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)), std::move(values), param));
}

py::tuple tupleOf(const std::vector<double>& v) {
  py::tuple t(v.size());
  for (size_t i = 0; i < v.size(); ++i) t[i] = py::float_(v[i]);
  return t;
}

// How an edit is recorded: the value's repr, or for arrays (whose repr elides) their size and
// the digest of their content.
std::string editText(const nx::FixedParameter& decl, const nx::FieldValue& v,
                     const py::handle& value) {
  if (const auto* m = std::get_if<std::shared_ptr<const nx::MeasuredMatrix>>(&v))
    return matrixEditText(**m);
  if (const auto* c = std::get_if<std::shared_ptr<const nx::ConcentrationMap>>(&v))
    return "<map " + std::to_string((*c)->height) + "x" + std::to_string((*c)->width) + " digest " +
           std::to_string((*c)->digest) + ">";
  (void)decl;
  return py::repr(value).cast<std::string>();
}

} // namespace

py::object fieldToPython(const nx::FixedParameter& decl, const nx::FieldValue& v) {
  const std::string type = decl.type;
  if (std::holds_alternative<std::monostate>(v)) return py::none();
  if (const double* x = std::get_if<double>(&v))
    return type == "integer" ? py::object(py::int_(static_cast<long long>(*x)))
                             : py::object(py::float_(*x));
  if (const auto* n = std::get_if<std::vector<double>>(&v)) {
    if (type != "integers") return tupleOf(*n);
    py::tuple t(n->size());
    for (size_t i = 0; i < n->size(); ++i) t[i] = py::int_(static_cast<long long>((*n)[i]));
    return t;
  }
  if (const auto* s = std::get_if<std::string>(&v)) return py::str(*s);
  if (const auto* p = std::get_if<nx::Vec3d>(&v)) return py::make_tuple(p->x, p->y, p->z);
  if (const auto* s = std::get_if<nx::SpectrumDesc>(&v)) return spectrumToPython(*s);
  if (const auto* m = std::get_if<std::shared_ptr<const nx::MeasuredMatrix>>(&v))
    return matrixToPython(**m);
  const auto& map = *std::get<std::shared_ptr<const nx::ConcentrationMap>>(v);
  py::array_t<float> a({map.height, map.width});
  std::copy(map.values.begin(), map.values.end(), a.mutable_data());
  return a;
}

nx::FieldValue fieldFromPython(const nx::FixedParameter& decl, const py::handle& value,
                               const std::string& param, const nx::SourceLocation& loc) {
  const std::string type = decl.type;
  const char* p = param.c_str();
  if (type == "integer")
    return static_cast<double>(integerArgument(value, p, LLONG_MIN, LLONG_MAX));
  if (type == "integers") {
    const std::vector<long long> v = integersArgument(value, p, 2);
    return std::vector<double>(v.begin(), v.end());
  }
  if (type == "text" || type == "name") return stringArgument(value, p);
  if (value.is_none()) return nx::FieldValue(); // absent (refused where a value is required)
  if (type == "number")
    return decl.range ? rangedArgument(value, param, *decl.range)
                      : numberArgument(value, p, -1e300, 1e300);
  if (type == "numbers") return numberListArgument(value, p, 0);
  if (type == "point" || type == "vector") {
    const std::vector<double> v = numbersArgument(value, p, 3);
    for (double x : v)
      if (std::abs(x) > nx::kMaxSceneCoordinate)
        throw py::value_error(param + ": expected coordinates within 1e12, found " +
                              py::str(py::float_(x)).cast<std::string>());
    return nx::Vec3d(v[0], v[1], v[2]);
  }
  if (type == "spectrum") return spectrumFromPython(value, param, loc);
  if (type == "matrix") return matrixFromPython(value, param);
  if (type == "concentration map") return mapFromPython(value, param);
  throw py::type_error(param + ": a declared type without a Python form ('" + type + "')");
}

py::object getField(const SceneState& state, const std::string& name) {
  const nx::FixedParameter& decl = nx::fixedParameter(nx::sceneFieldKey(name));
  return fieldToPython(decl, nx::sceneField(state.desc, name)); // errors: nxrender.Error
}

void setField(SceneState& state, const std::string& name, const py::handle& value) {
  const nx::FixedParameter& decl = nx::fixedParameter(nx::sceneFieldKey(name));
  // Located at its own name: a value set from Python that a render refuses is reported as
  // "objects[1].fluorescence.emission: ...", not at the file's <settings>.
  const nx::FieldValue v = fieldFromPython(decl, value, name, nx::SourceLocation{name, 0});
  try {
    state.setField(name, v, editText(decl, v, value)); // refusals: nxrender.Error (ValueError)
  } catch (const nx::FieldTypeError& e) {
    throw py::type_error(e.what());
  }
}

} // namespace nxpy
