#include "integrators/materials/material_kind.h"

#include <cmath>
#include <cstdlib>

#include "core/error.h"
#include "core/number_text.h"
#include "core/params/material_parameters.h"
#include "core/text_table.h"
#include "spectra/spectrum_bounds.h"

namespace nx {

// The kinds (one file each in kinds/).
extern const MaterialKindSpec kMatteKind, kMetalKind, kPlasticKind, kMirrorKind, kGlassKind,
    kDiamondKind, kTranslucentKind, kTransparentKind, kDefaultKind, kDiffuseKind, kInterfaceKind,
    kThinGlassKind, kConductorKind, kCoatedKind, kRoughMatteKind;

std::span<const MaterialKindSpec* const> materialKinds() {
  static const MaterialKindSpec* const kinds[] = {
      &kMatteKind,     &kMetalKind,       &kPlasticKind,     &kMirrorKind,  &kGlassKind,
      &kDiamondKind,   &kTranslucentKind, &kTransparentKind, &kDefaultKind, &kDiffuseKind,
      &kInterfaceKind, &kThinGlassKind,   &kConductorKind,   &kCoatedKind,  &kRoughMatteKind};
  return kinds;
}

const MaterialKindSpec* findMaterialKind(std::string_view name) {
  for (const MaterialKindSpec* k : materialKinds())
    if (name == k->name) return k;
  return nullptr;
}

std::string materialKindList() {
  std::vector<std::string> names;
  for (const MaterialKindSpec* k : materialKinds()) names.push_back(k->name);
  return listWithOr(names);
}

const KindParameter* MaterialKindSpec::param(std::string_view n) const {
  for (const KindParameter& p : params)
    if (n == p.name) return &p;
  return nullptr;
}

double MaterialKindSpec::numberDefault(std::string_view n) const {
  const KindParameter* p = param(n);
  const char* end = nullptr;
  const double v = p ? strtodC(p->defaultText, &end) : NAN;
  if (!p || end == p->defaultText || *end != '\0')
    throw Error(std::string("material kind '") + name + "' declares no number default for <" +
                std::string(n) + ">"); // a defect of the kind's declaration
  return v;
}

void checkMaterialParameters(const MaterialKindSpec& kind, const ParameterSet& params) {
  for (const Parameter& q : params.items()) {
    if (kind.param(q.name)) continue;
    std::vector<std::string> taken;
    for (const KindParameter& p : kind.params) taken.push_back(std::string("<") + p.name + ">");
    std::string why;
    for (const auto& [param, reason] : kind.refusals)
      if (q.name == param) why = std::string(" (") + reason + ")";
    throw Error(q.loc.str() + ": expected " +
                (taken.empty() ? std::string("no parameters") : "only " + listWithOr(taken)) +
                " on " + kind.name + ", found <" + q.name + ">" + why);
  }
}

std::string tracedRange() {
  return numberText(kTraceMinNm) + "-" + numberText(kTraceMaxNm) + " nm";
}

void checkUnitRange(const Spectrum& s, const SourceLocation& loc, const char* what) {
  const SpectrumExtremes e = spectrumExtremes(s, kTraceMinNm, kTraceMaxNm);
  if (e.min >= 0 && e.max <= 1) return;
  const bool low = !(e.min >= 0);
  throw Error(loc.str() + ": expected a " + what + " within [0, 1] at every wavelength of " +
              tracedRange() + ", found " + numberText(low ? e.min : e.max) + " at " +
              numberText(low ? e.minNm : e.maxNm) + " nm");
}

void setSurfaceReflectance(Material& m, const ParameterSet& p, const MaterialInputs& in, bool clear,
                           const char* what) {
  const SpectrumDesc* reflectance = p.get<SpectrumDesc>("reflectance");
  const auto* color = p.get<std::array<double, 4>>("color");
  // Each mode prefers its own tag (<reflectance> in spectral_mcpt, <color> in rt and mcpt)
  // and falls back on the other, so every scene renders in every mode.
  const bool useSpectrum = reflectance && (in.spectral || !color);
  if (useSpectrum && reflectance->kind == SpectrumDesc::Kind::Texture) {
    m.texture = in.texture(*reflectance);
    m.reflectance = Spectrum(ConstantSpectrum{0.5}); // unused: the texture replaces it
  } else if (useSpectrum) {
    m.reflectance = in.spectrum(*reflectance, SpectrumRole::Reflectance);
    checkUnitRange(m.reflectance, reflectance->loc, what);
  } else if (color) {
    m.reflectance = in.srgbReflectance({(*color)[0], (*color)[1], (*color)[2]});
  } else if (clear) {
    m.reflectance = Spectrum(ConstantSpectrum{1.0});
  } else if (in.emitter) {
    m.reflectance = Spectrum(ConstantSpectrum{0.0}); // a black emitter
  } else {
    throw Error(in.objectLoc.str() + ": expected <reflectance> or <color> on a non-emitting " +
                in.kindName + " object, found neither");
  }
}

void setFluorescence(Material& m, const ParameterSet& p, const MaterialInputs& in) {
  const FluorescenceDesc* f = p.get<FluorescenceDesc>("fluorescence");
  if (!f) return;
  if (f->concentrationCsv || f->concentration) {
    if (f->matrixCsv || f->matrix)
      throw Error(f->loc.str() + ": expected a concentration map only with the parametric model "
                                 "or an imported EEM, found one with a measured matrix");
    m.concentration = in.concentrationMap(*f);
  }
  if (f->matrixCsv || f->matrix || f->eem) {
    m.reradiation = in.measuredMatrix(*f, m.texture ? nullptr : &m.reflectance);
    if (f->eem) return; // an imported EEM is fluorescence only by nature (the import notes it)
    // Which elastic part the surface has: the matrix's diagonal, or (a fluorescence-only
    // matrix, as an instrument EEM gives) the material's reflectance; the latter is said.
    if (m.reradiation->elasticFromReflectance())
      in.warn(f->loc.str() + ": warning: the measured matrix " +
              (f->matrixCsv ? *f->matrixCsv : std::string("given as numbers")) +
              (m.reradiation->zeroDiagonal()
                   ? " has a diagonal of zeros (a fluorescence-only measurement), taken as no "
                     "diagonal: its elastic reflectance is the material's "
                   : " has no diagonal (no excitation wavelength equals an emission one): its "
                     "elastic reflectance is the material's ") +
              (p.has("reflectance") ? "<reflectance>"
               : p.has("color")     ? "<color>"
                                    : "reflectance") +
              (m.texture ? " (a texture: the energy of each texel is not checked)" : ""));
    return;
  }
  if (f->spectra) { // a dye as a datasheet gives it: the separable matrix
    const Spectrum a = in.spectrum(f->spectra->absorptance, SpectrumRole::Reflectance);
    // (the emission's scale is any: its shape is what counts, not a light's limit)
    const Spectrum e = in.spectrum(f->spectra->emission, SpectrumRole::EmissionShape);
    std::string warning;
    m.reradiation = std::make_shared<const ReradiationMatrix>(
        separableMatrix(a, e, f->quantumYield.value_or(1), false, f->loc.str(), &warning));
    if (!warning.empty()) in.warn(warning);
    return;
  }
  m.fluorescenceModel = in.fluorescenceModel(*f);
  m.reradiation =
      std::make_shared<const ReradiationMatrix>(ReradiationMatrix::fromModel(*m.fluorescenceModel));
}

void setGgxAlpha(Material& m, const ParameterSet& p) {
  const Parameter *a = p.find("alpha"), *au = p.find("alpha_u"), *av = p.find("alpha_v");
  if (a && (au || av))
    throw Error(a->loc.str() + ": expected either <alpha> or <alpha_u> and <alpha_v>, found both");
  if ((au != nullptr) != (av != nullptr))
    throw Error((au ? au : av)->loc.str() +
                ": expected <alpha_u> and <alpha_v> together, found only one of them");
  const double u = a ? std::get<double>(a->value) : au ? std::get<double>(au->value) : 0.0;
  const double v = a ? std::get<double>(a->value) : av ? std::get<double>(av->value) : 0.0;
  m.alphaU = static_cast<float>(u);
  m.alphaV = static_cast<float>(v);
}

void setCoating(Material& m, const ParameterSet& p, const MaterialInputs& in) {
  const CoatingDesc* c = p.get<CoatingDesc>("coating");
  if (!c) return;
  m.coatingNm = static_cast<float>(c->thicknessNm);
  m.coatingIor = in.ior(c->ior);
}

} // namespace nx
