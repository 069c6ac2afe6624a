#pragma once
// A homogeneous participating medium: absorption and scattering coefficients (spectra, per
// scene unit of length), a Henyey-Greenstein lobe, and optionally a fluorescent dye, the same
// everywhere inside its shape.

// The kind is one of the scene format (<medium type="homogeneous">, the default): its
// parameters and its build from them are declared below, after the evaluation.

#include <cmath>
#include <memory>
#include <optional>
#include <span>

#include "core/error.h"
#include "core/params/parameter_set.h"
#include "integrators/materials/material_kind.h"
#include "spectra/reradiation_matrix.h"
#include "spectra/sampled_wavelengths.h"
#include "spectra/spectrum.h"
#include "spectra/spectrum_bounds.h"

namespace nx {

/// Largest absorption or scattering coefficient of a medium (per scene unit of length): a
/// mean free path of 1e-9 units, far below any scene's scale.
inline constexpr double kMaxMediumCoefficient = 1e9;

/// What a medium kind's build asks of the scene: spectra resolved and checked, the dye's model
/// checked. Implemented by the scene builder; called once per medium, never while rendering.
class MediumInputs {
public:
  virtual ~MediumInputs() = default;
  /// A spectrum reference resolved (coefficients take the media tables' names).
  virtual Spectrum spectrum(const SpectrumDesc& d, SpectrumRole role) const = 0;
  /// Throws "<loc>: expected an emission within [0, 1e12] ..." unless `s` is one.
  virtual void checkEmission(const Spectrum& s, const SourceLocation& loc) const = 0;
  /// The parametric re-radiation model, checked.
  virtual FluorescenceModel fluorescenceModel(const FluorescenceDesc& d) const = 0;
  /// Records a warning ("file:line: warning: ...") the render prints.
  virtual void warn(const std::string& message) const = 0;
};

/// The medium filling a closed shape.
///
/// A dye (fluorescence model, docs/media.md) absorbs sigma_f(l) = peak a(l) (a: the model's
/// absorption curve with peak 1, per 5 nm bin of the re-radiation matrix) on top of sigma_a,
/// and re-emits isotropically: light at emission wavelength l_o arises per unit length from
/// the fluence at every excitation bin i as peak M[i][o] / (4 pi), with M the model's matrix
/// for a peak absorptance of 1 (M[i][o] = a_i Q e_o l_i / l_o). Its "in-scattering"
/// coefficient at l_o is thus sigma_fl(l_o) = peak c(o), c the matrix's column sum.
struct HomogeneousMedium {
  Spectrum sigmaA;                              ///< absorption coefficient (other than the dye's)
  Spectrum sigmaS;                              ///< scattering coefficient
  float g = 0;                                  ///< Henyey-Greenstein mean cosine
  std::shared_ptr<const ReradiationMatrix> dye; ///< the dye's matrix (peak absorptance 1), or null
  float dyePeak = 0; ///< the dye's peak absorption coefficient per unit length
  /// Emitted radiance Le: the medium is a source sigma_a Le per unit length and solid angle
  /// (Kirchhoff: deep inside, the radiance tends to Le), or null
  std::optional<Spectrum> emission;

  /// The emission source sigma_a Le of the lanes (sigma_a without the dye's absorption).
  SampledSpectrum emissionSource(const SampledWavelengths& lambda) const {
    SampledSpectrum a, le;
    sigmaA.evaluate(lambda, a);
    emission->evaluate(lambda, le);
    return a * le;
  }

  /// The lanes' coefficients: sigma_a + sigma_f (all absorption), sigma_s, and the dye's
  /// in-scattering sigma_fl (zero without a dye).
  void coefficients(const SampledWavelengths& lambda, SampledSpectrum& absorption,
                    SampledSpectrum& scattering, SampledSpectrum& fluorescent) const {
    sigmaA.evaluate(lambda, absorption);
    sigmaS.evaluate(lambda, scattering);
    fluorescent = SampledSpectrum();
    if (!dye) return;
    for (int i = 0; i < kLanes; ++i) {
      const int bin = ReradiationMatrix::binOf(lambda.lambda[i]);
      if (bin < 0) continue;
      absorption[i] += dyePeak * static_cast<float>(dye->absorptance(bin));
      fluorescent[i] = dyePeak * static_cast<float>(dye->columnSum(bin));
    }
  }
};

/// The homogeneous medium kind.
struct HomogeneousMediumKind {
  static constexpr const char* kName = "homogeneous";
  static constexpr const char* kDoc =
      "the same absorption, scattering (Henyey-Greenstein), emission and dye everywhere inside "
      "its sphere or closed mesh";
  /// Its parameters.
  static std::span<const TakenParameter> parameters() {
    static const TakenParameter p[] = {
        {differentiable({"sigma_a", ParamType::Spectrum, "1/scene unit", nullptr,
                         "absorption coefficient (besides the dye's); scale=\"...\" multiplies it",
                         "water:absorption"}),
         "", true},
        {differentiable(
             {"sigma_a_scale", ParamType::Number, "1", &kPositiveScaleRange,
              "the factor on <sigma_a> (its scale=\"...\", e.g. 0.01 for a per-metre table in "
              "centimetres)",
              "0.01", "", "coefficient scale"}),
         "1"},
        {differentiable({"sigma_s", ParamType::Spectrum, "1/scene unit", nullptr,
                         "scattering coefficient; scale=\"...\" multiplies it", "0.5"}),
         "", true},
        {differentiable({"sigma_s_scale", ParamType::Number, "1", &kPositiveScaleRange,
                         "the factor on <sigma_s> (its scale=\"...\")", "0.01", "",
                         "coefficient scale"}),
         "1"},
        {differentiable(
             {"g", ParamType::Number, "1", &kPhaseGRange, "Henyey-Greenstein mean cosine", "0.3"}),
         "0"},
        {{"fluorescence", ParamType::Dye, "", nullptr,
          "a dissolved fluorescent dye: the parametric model, its <peak> the dye's peak "
          "absorption coefficient per unit length (added to sigma_a)",
          "<absorption>blue</absorption><stokes>60</stokes><peak>2</peak>"},
         ""},
        {differentiable(
             {"emission", ParamType::Spectrum, "W m^-2 sr^-1 nm^-1", nullptr,
              "emitted radiance Le: the medium emits sigma_a Le per unit length (Kirchhoff)",
              "D65"}),
         ""},
        {differentiable({"emission_scale", ParamType::Number, "1", &kEmissionScaleRange,
                         "the factor on <emission> (its scale=\"...\")", "2", "",
                         "emission scale"}),
         "1"},
    };
    return p;
  }
  /// Builds it from its checked parameters: coefficients within [0, kMaxMediumCoefficient]
  /// over the traced range, emission only where it absorbs.
  static HomogeneousMedium build(const ParameterSet& p, const MediumInputs& in) {
    HomogeneousMedium m;
    const auto coefficient = [&](const char* name) {
      const SpectrumDesc& d = *p.get<SpectrumDesc>(name);
      const Spectrum s =
          forRendering(in.spectrum(d, SpectrumRole::Coefficient)
                           .scaled(p.number(std::string(name) + "_scale").value_or(1)));
      return std::pair<Spectrum, const SpectrumDesc*>{s, &d};
    };
    const auto [sigmaA, aDesc] = coefficient("sigma_a");
    const auto [sigmaS, sDesc] = coefficient("sigma_s");
    m.sigmaA = sigmaA;
    m.sigmaS = sigmaS;
    for (const auto& [sp, desc, what] :
         {std::tuple{&m.sigmaA, aDesc, "sigma_a"}, std::tuple{&m.sigmaS, sDesc, "sigma_s"}}) {
      const SpectrumExtremes e = spectrumExtremes(*sp, kTraceMinNm, kTraceMaxNm);
      if (!(e.min >= 0 && e.max <= kMaxMediumCoefficient))
        throw Error(desc->loc.str() + ": expected " + what + " within [0, " +
                    numberText(kMaxMediumCoefficient) +
                    "] per unit length at every wavelength of " + tracedRange() + ", found " +
                    (std::isnan(e.min) ? std::string("a non-finite value")
                                       : numberText(e.min < 0 ? e.min : e.max) + " at " +
                                             numberText(e.min < 0 ? e.minNm : e.maxNm) + " nm"));
    }
    m.g = static_cast<float>(p.number("g").value_or(0));
    if (const SpectrumDesc* emission = p.get<SpectrumDesc>("emission")) {
      // The source is sigma_a Le: a medium that absorbs nothing cannot emit (Kirchhoff).
      if (!(spectrumExtremes(m.sigmaA, kTraceMinNm, kTraceMaxNm).max > 0))
        throw Error(emission->loc.str() +
                    ": expected a medium that absorbs (sigma_a > 0 somewhere in " + tracedRange() +
                    ") for an <emission>: the medium emits sigma_a Le per unit length, found "
                    "sigma_a = 0 everywhere");
      const Spectrum le = in.spectrum(*emission, SpectrumRole::Emission)
                              .scaled(p.number("emission_scale").value_or(1));
      in.checkEmission(le, emission->loc);
      m.emission = forRendering(le);
    }
    if (const FluorescenceDesc* dye = p.get<FluorescenceDesc>("fluorescence");
        dye && dye->spectra) { // a dye as a datasheet gives it: its absorptance is a shape
      if (!dye->peakAbsorptance)
        throw Error(dye->loc.str() + ": expected a <peak> (the dye's peak absorption "
                                     "coefficient per unit length), found none");
      m.dyePeak = static_cast<float>(*dye->peakAbsorptance);
      std::string warning;
      m.dye = std::make_shared<const ReradiationMatrix>(
          separableMatrix(in.spectrum(dye->spectra->absorptance, SpectrumRole::Coefficient),
                          in.spectrum(dye->spectra->emission, SpectrumRole::EmissionShape),
                          dye->quantumYield.value_or(1), true, dye->loc.str(), &warning));
      if (!warning.empty()) in.warn(warning);
    } else if (dye) {
      FluorescenceModel model = in.fluorescenceModel(*dye);
      m.dyePeak = static_cast<float>(model.peakAbsorptance); // the coefficient, per unit length
      model.peakAbsorptance = 1;
      m.dye = std::make_shared<const ReradiationMatrix>(ReradiationMatrix::fromModel(model));
    }
    return m;
  }
};

} // namespace nx
