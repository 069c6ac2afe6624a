#pragma once
// What a light kind declares and needs: its parameters (each with its type, unit, range and
// meaning: the scene loader reads them by it), and what its build asks of the scene. A kind is
// one header of integrators/lights/kinds/ (its parameters, build, sampling and power); the
// registry (light_kinds.h) lists the kinds in one variant.

#include <array>
#include <cmath>
#include <memory>
#include <span>
#include <string>

#include "core/math_util.h"
#include "core/params/parameter_set.h"
#include "core/sampler.h"
#include "integrators/lights/light_bounds.h"
#include "integrators/lights/light_sample.h"
#include "integrators/materials/material_kind.h"
#include "io/spectral_exr.h"
#include "spectra/spectrum.h"

namespace nx {

/// One parameter a light kind takes: its declaration and its default.
using LightParameter = TakenParameter;

/// What a light kind's build asks of the scene: spectra resolved and checked. Implemented by
/// the scene builder; called once per light, never while rendering.
class LightInputs {
public:
  virtual ~LightInputs() = default;
  /// A spectrum reference resolved (emissions checked to lie within [0, kMaxEmission]).
  virtual Spectrum spectrum(const SpectrumDesc& d, SpectrumRole role) const = 0;
  /// An RGB intensity upsampled to a spectrum (rt and mcpt's <color>).
  virtual Spectrum srgbIntensity(const std::array<double, 3>& rgb) const = 0;
  /// What the light traces for emission `shape` (as written in the scene) times `factor`:
  /// forRendering(shape.scaled(factor)), or in a relightable build the factor alone (flat),
  /// the shape kept for the light's group (RelightSpectra).
  virtual Spectrum emitted(const Spectrum& shape, double factor) const = 0;
  /// Throws "<loc>: expected an emission within [0, 1e12] ..." unless `s` is one.
  virtual void checkEmission(const Spectrum& s, const SourceLocation& loc) const = 0;
  /// A spectral EXR read (its bytes in the render key); errors name `loc` and the file.
  virtual std::shared_ptr<const SpectralImage> spectralImage(const std::string& path,
                                                             const SourceLocation& loc) const = 0;
  /// Notes data tabulated over [loNm, hiNm] only (0 beyond): a render tracing beyond warns,
  /// saying how to choose (`choice`, e.g. "write <extrapolate>hold</extrapolate> in the <light>").
  virtual void tabulated(const SourceLocation& loc, const std::string& what, double loNm,
                         double hiNm, const std::string& choice) const = 0;

  bool spectral = true; ///< spectral_mcpt (else rt or mcpt: <color> preferred)
  SourceLocation loc;   ///< the <light> element
};

/// Where a light is (every positioned kind's first parameter).
inline const LightParameter kLightPosition{
    {"position", ParamType::Point, "scene units", nullptr, "where it is", "0, 5, 0"}, "", true};
/// The factor on a light's <emission>, written as its scale="...".
inline const LightParameter kLightEmissionScale{
    differentiable({"emission_scale", ParamType::Number, "1", &kEmissionScaleRange,
                    "the factor on <emission> (its scale=\"...\")", "2", "", "emission scale"}),
    "1"};

/// <emission at="d">: the emission is the spectral irradiance E the lamp gives on its axis at
/// distance d (scene units, the length unit of E's area; a lamp measured with a
/// spectroradiometer at 500 mm in a scene in millimetres: at="500" and E per mm^2), at normal
/// incidence; the intensity is I = E d^2 (inverse square law, the far field of the lamp).
inline const LightParameter kLightEmissionAt{
    {"emission_at", ParamType::Number, "scene units", &kMeasuredDistanceRange,
     "<emission> is the irradiance on the axis at this distance (its at=\"...\"): I = E d^2", "500",
     "", "measuring distance"},
    ""};

/// A delta light's sample from p: the direction and distance to `position` and the intensity
/// times factor(wi) / d^2 (pdf 1); false where it sends nothing (factor 0).
template <class Factor>
bool sampleDeltaLight(const Vec3& position, const Spectrum& intensity, const Vec3& p,
                      const SampledWavelengths& lambda, LightSample& out, Factor&& factor) {
  const Vec3 toLight = position - p;
  const float d2 = dot(toLight, toLight);
  if (!(d2 > 0)) return false;
  out.distance = std::sqrt(d2);
  out.wi = toLight / out.distance;
  const float s = factor(out.wi);
  if (!(s > 0)) return false;
  out.p = position;
  out.pError = Vec3(0, 0, 0);
  out.n = Vec3(0, 0, 0);
  intensity.evaluate(lambda, out.radiance);
  out.radiance *= s / d2;
  out.pdf = 1;
  out.delta = true;
  return true;
}

/// Integral of a spectrum over the traced range (1 nm trapezoids): the lights' power weights.
inline double tracedIntegral(const Spectrum& s) {
  double sum = 0.5 * (s(kTraceMinNm) + s(kTraceMaxNm));
  for (double nm = kTraceMinNm + 1; nm < kTraceMaxNm; nm += 1) sum += s(nm);
  return sum;
}

/// A delta light's intensity from its parameters: <emission> (times <emission> scale="...",
/// times d^2 for an irradiance measured at="d") in
/// spectral_mcpt or without a <color>, else its RGB <color>; checked and prepared for
/// rendering.
inline Spectrum lightIntensity(const ParameterSet& p, const LightInputs& in) {
  const SpectrumDesc* emission = p.get<SpectrumDesc>("emission");
  const auto* color = p.get<std::array<double, 4>>("color");
  Spectrum shape;
  double factor = 1;
  if (emission && (in.spectral || !color)) {
    const double d = p.number("emission_at").value_or(1.0); // irradiance at d: I = E d^2
    shape = in.spectrum(*emission, SpectrumRole::Emission);
    factor = p.number("emission_scale").value_or(1.0) * d * d;
  } else if (color)
    shape = in.srgbIntensity({(*color)[0], (*color)[1], (*color)[2]});
  in.checkEmission(shape.scaled(factor), emission ? emission->loc : in.loc);
  return in.emitted(shape, factor);
}

} // namespace nx
