#include "core/params/parameter_set.h"

#include <algorithm>
#include <sstream>

#include "core/hash.h"

namespace nx {

const char* paramTypeName(ParamType t) {
  switch (t) {
  case ParamType::Number:
    return "number";
  case ParamType::Rgb:
    return "rgb";
  case ParamType::Spectrum:
    return "spectrum";
  case ParamType::Reflectance:
    return "spectrum or texture";
  case ParamType::Ior:
    return "ior";
  case ParamType::Fluorescence:
    return "fluorescence";
  case ParamType::Coating:
    return "coating";
  case ParamType::Name:
    return "name";
  case ParamType::Point:
    return "point";
  case ParamType::File:
    return "file";
  case ParamType::Transform:
    return "transform";
  case ParamType::Dye:
    return "dye";
  case ParamType::Reals:
    return "rows of numbers";
  case ParamType::Indices:
    return "rows of indices";
  }
  return "?";
}

const Parameter* ParameterSet::find(std::string_view name) const {
  for (const Parameter& p : items_)
    if (p.name == name) return &p;
  return nullptr;
}

const SourceLocation& ParameterSet::locOf(std::string_view name,
                                          const SourceLocation& fallback) const {
  const Parameter* p = find(name);
  return p ? p->loc : fallback;
}

void ParameterSet::set(Parameter p) {
  for (Parameter& q : items_)
    if (q.name == p.name) {
      q = std::move(p);
      return;
    }
  items_.push_back(std::move(p));
}

void ParameterSet::erase(std::string_view name) {
  items_.erase(std::remove_if(items_.begin(), items_.end(),
                              [&](const Parameter& p) { return p.name == name; }),
               items_.end());
}

namespace {

// The canonical writer names every field of every value type (else two materials differing
// only in it would be shared): tests/build_checks/check_fields_written.py checks each is named.

struct CanonicalWriter {
  std::ostringstream& t;
  void operator()(double v) const { t << v; }
  void operator()(const std::array<double, 4>& c) const {
    t << c[0] << ',' << c[1] << ',' << c[2] << ',' << c[3];
  }
  void operator()(const SpectrumDesc& s) const {
    t << static_cast<int>(s.kind) << ',' << static_cast<int>(s.extrapolate) << ','
      << (s.clampNegative ? "clamp," : "") << s.name.size() << ':' << s.name << ',' << s.number
      << ',' << s.path.size() << ':' << s.path << ',' << s.column.size() << ':' << s.column << ','
      << s.texture.size() << ':' << s.texture << ',' << s.nm.size() << ':';
    for (size_t i = 0; i < s.nm.size(); ++i) t << s.nm[i] << ':' << s.value[i] << ' ';
    if (s.texels) t << "texels:" << s.texels->digest;
  }
  void operator()(const IorDesc& d) const {
    t << static_cast<int>(d.kind) << ',' << d.value << ',' << d.name.size() << ':' << d.name << ','
      << d.coefficients.size() << ':';
    for (double c : d.coefficients) t << c << ' ';
  }
  void operator()(const FluorescenceDesc& f) const {
    auto opt = [&](const std::optional<double>& v) {
      if (v)
        t << *v << ',';
      else
        t << "-,";
    };
    auto text = [&](const std::optional<std::string>& v) {
      if (v)
        t << v->size() << ':' << *v << ',';
      else
        t << "-,";
    };
    text(f.absorptionName);
    opt(f.absorptionNm), opt(f.stokesNm), opt(f.widthNm), opt(f.skew), opt(f.quantumYield);
    opt(f.peakAbsorptance);
    text(f.matrixCsv);
    if (f.matrix) t << "matrix:" << f.matrixDigest; // the content of a matrix given as numbers
    text(f.concentrationCsv);
    if (f.concentration) t << "concentration:" << f.concentration->digest << ',';
    if (f.eem) { // the files' bytes join the render key when they are read
      const EemDesc& e = *f.eem;
      const EemLayout& l = e.layout;
      t << "eem:" << e.file.size() << ':' << e.file << ',' << l.emissionRows << l.energyUnits
        << l.secondOrder << l.meanEmissionShape << ',' << l.rayleighWidthNm << ',' << l.ramanShiftCm
        << ',' << l.ramanWidthNm << ',' << e.referenceFile.size() << ':' << e.referenceFile << ','
        << e.referenceYield << ',' << e.referenceAbsorptance << ',';
      opt(e.referenceExcitationNm);
      if (e.absorptance) (*this)(*e.absorptance);
    }
    if (f.spectra) { // the separable form: its two spectra
      t << "spectra:";
      (*this)(f.spectra->absorptance);
      t << ';';
      (*this)(f.spectra->emission);
      t << ';';
    }
  }
  void operator()(const CoatingDesc& c) const {
    t << c.thicknessNm << ',';
    (*this)(c.ior);
  }
  void operator()(const std::string& s) const { t << s.size() << ':' << s; }
  void operator()(const Vec3d& v) const { t << v.x << ',' << v.y << ',' << v.z; }
  void operator()(const AffineDesc& a) const {
    for (const auto& row : a.m) t << row[0] << ',' << row[1] << ',' << row[2] << ',';
    (*this)(a.t);
  }
  void operator()(const ArrayDesc& a) const {
    t << (a.reals ? "reals:" : "indices:") << a.columns << ':' << a.rows() << ':' << a.digest;
  }
};

} // namespace

std::string canonicalText(const ParamValue& v) {
  std::ostringstream t;
  t.precision(17);
  t << v.index() << '|';
  std::visit(CanonicalWriter{t}, v);
  return t.str();
}

std::string ParameterSet::canonicalText() const {
  std::vector<const Parameter*> sorted;
  for (const Parameter& p : items_) sorted.push_back(&p);
  std::sort(sorted.begin(), sorted.end(),
            [](const Parameter* a, const Parameter* b) { return a->name < b->name; });
  std::string out;
  for (const Parameter* p : sorted) out += p->name + '=' + nx::canonicalText(p->value) + ';';
  return out;
}

} // namespace nx
