#include "integrators/scene_references.h"

#include <cmath>

#include "core/error.h"
#include "core/file_text.h"
#include "core/hash.h"
#include "core/text_table.h"
#include "integrators/materials/material_kind.h"
#include "spectra/illuminants.h"
#include "spectra/named_spectra.h"
#include "spectra/spectrum_bounds.h"
#include "spectra/water.h"

namespace nx {

SceneReferences::SceneReferences(const SceneDesc& desc) : digest_(desc.textDigest) {
  for (const auto& s : desc.spectra) named_[s.name] = &s;
}

std::string SceneReferences::readFile(const std::string& path, std::uintmax_t maxBytes,
                                      const char* what) const {
  std::string bytes = readRegularFile(path, maxBytes, what);
  fold(bytes, path);
  return bytes;
}

void SceneReferences::fold(std::string_view bytes, const std::string& path) const {
  digest_ = fnv1a64(bytes, fnv1a64(std::string_view(path.c_str(), path.size() + 1), digest_));
}

// Resolves a spectrum reference; emission spectra are checked to lie within [0, 1e12].
Spectrum SceneReferences::resolve(const SpectrumDesc& s, SpectrumRole role) const {
  Spectrum r = resolveUnchecked(s, role, 0, s.extrapolate);
  if (role == SpectrumRole::Emission) checkEmission(r, s.loc);
  return r;
}

// A table's behaviour beyond its wavelengths: held, zero by choice, or zero and remembered
// for a warning when a render traces beyond it.
Spectrum SceneReferences::extrapolated(Spectrum r, SpectrumDesc::Extrapolation mode,
                                       const SourceLocation& loc, const std::string& what) const {
  if (const auto* t = std::get_if<TabulatedSpectrum>(&r.kind())) {
    if (mode != SpectrumDesc::Extrapolation::Unset) {
      TabulatedSpectrum chosen = *t;
      chosen.holdEnds = mode == SpectrumDesc::Extrapolation::Hold;
      return Spectrum(std::move(chosen), r.scale());
    }
    if (!t->holdEnds) // built-in tables that hold their ends need no warning
      tables_.push_back({loc.str(), what, t->nm.front(), t->nm.back()});
  }
  return r;
}

// `mode`: the extrapolation asked for by the outermost reference that names one (a use of a
// <spectrum> definition overrides the definition's own).
Spectrum SceneReferences::resolveUnchecked(const SpectrumDesc& s, SpectrumRole role, int depth,
                                           SpectrumDesc::Extrapolation mode) const {
  if (mode == SpectrumDesc::Extrapolation::Unset) mode = s.extrapolate;
  try {
    switch (s.kind) {
    case SpectrumDesc::Kind::Number:
      return Spectrum(ConstantSpectrum{s.number});
    case SpectrumDesc::Kind::Pairs:
      return extrapolated(
          Spectrum(clamped(makeTabulated(s.nm, s.value, "nm:value pairs"), s, "nm:value pairs")),
          mode, s.loc, "nm:value pairs");
    case SpectrumDesc::Kind::CsvFile: {
      const std::string what = s.column.empty() ? s.path : s.path + " (column " + s.column + ")";
      return extrapolated(
          Spectrum(
              clamped(parseSpectrumCsv(readFile(s.path, 64u << 20, "table file"), s.path, s.column),
                      s, what)),
          mode, s.loc, what);
    }
    case SpectrumDesc::Kind::Name:
      break;
    case SpectrumDesc::Kind::Texture: // the loader allows textures on <reflectance> only
      throw Error("expected a spectrum, found a texture");
    }
  } catch (const Error& e) {
    throw Error(s.loc.str() + ": " + e.what());
  }
  if (auto it = named_.find(s.name); it != named_.end()) {
    if (depth > 16)
      throw Error(s.loc.str() +
                  ": expected spectrum definitions without a cycle, found one through '" + s.name +
                  "'");
    return resolveUnchecked(it->second->spectrum, role, depth + 1, mode);
  }
  if (role == SpectrumRole::Coefficient)
    if (auto c = namedMediumCoefficient(s.name)) return extrapolated(*c, mode, s.loc, s.name);
  if (role != SpectrumRole::Emission && role != SpectrumRole::EmissionShape) {
    if (auto r = namedReflectance(s.name)) return extrapolated(*r, mode, s.loc, s.name);
    throw Error(s.loc.str() + ": expected " +
                (role == SpectrumRole::Coefficient
                     ? "water:absorption, water:scattering (per metre), "
                     : "") +
                "a reflectance name (red, orange, yellow, green, blue, purple, uv, "
                "gray, const, null, colorchecker:<patch> (dark_skin, ..., black_2), or a "
                "<spectrum> of the scene), found '" +
                s.name + "'");
  }
  std::optional<Spectrum> e;
  try {
    e = namedEmission(s.name);
  } catch (const Error& err) {
    throw Error(s.loc.str() + ": " + err.what());
  }
  if (e) return extrapolated(*e, mode, s.loc, s.name);
  throw Error(s.loc.str() +
              ": expected an illuminant name (A, D50, D55, D65, D75, D<nn>, daylight:<K>, F1-F12, "
              "E, blackbody:<K>, bba, bbd50, bbd55, bbd65, bbd75, bl, or a <spectrum> of the "
              "scene), found '" +
              s.name + "'");
}

TabulatedSpectrum SceneReferences::clamped(TabulatedSpectrum t, const SpectrumDesc& s,
                                           const std::string& what) const {
  if (!s.clampNegative) return t;
  size_t count = 0;
  double lowest = 0;
  for (double& v : t.value)
    if (v < 0) ++count, lowest = std::min(lowest, v), v = 0;
  if (count > 0)
    warnings_.push_back(s.loc.str() + ": warning: " + std::to_string(count) + " of " +
                        std::to_string(t.value.size()) + " values of '" + what +
                        "' were negative (down to " + numberText(lowest) +
                        ") and were set to 0 (negative=\"clamp\")");
  return t;
}

// Emission (radiance, or a point light's intensity) within [0, kMaxEmission] everywhere.
void SceneReferences::checkEmission(const Spectrum& s, const SourceLocation& loc) {
  if (const std::string problem = emissionProblem(s); !problem.empty())
    throw Error(loc.str() + ": " + problem);
}

} // namespace nx
