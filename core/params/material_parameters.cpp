#include "core/params/material_parameters.h"

namespace nx {

std::span<const ParamSpec> materialParameters() {
  static const ParamSpec specs[] = {
      differentiable(
          {"color", ParamType::Rgb, "1", &kUnitRange,
           "sRGB colour R, G, B[, A] in [0, 1]: rt and mcpt upsample it to a reflectance; "
           "spectral_mcpt uses it when there is no <reflectance>",
           "0.8, 0.2, 0.1"}),
      differentiable(
          {"reflectance", ParamType::Reflectance, "1", nullptr,
           "reflectance (a dielectric's transmission tint) in [0, 1] at every wavelength, or a "
           "texture",
           "400:0.2, 700:0.8"}),
      {"roughness", ParamType::Number, "1", &kRoughnessRange,
       "weight r of the Lambertian lobe in Niixtracer's mixture (1 - r) mirror + r Lambertian",
       "0.5"},
      {"ior", ParamType::Ior, "1", &kIorRange,
       "index of refraction: a number, bk7, diamond, fused_silica, cauchy: A, B[, C] (um) or "
       "sellmeier: B1, B2, B3, C1, C2, C3 (um^2)",
       "1.4"},
      {"fluorescence", ParamType::Fluorescence, "-", nullptr,
       "re-radiation of the diffuse lobe: the parametric model, a measured matrix or an "
       "instrument EEM (docs/fluorescence.md, docs/eem-import.md)",
       "<absorption>450</absorption><stokes>60</stokes>"},
      {"eta", ParamType::Spectrum, "1", nullptr,
       "real part of a conductor's complex index eta + i k, within [0.001, 1000]", "0.2", "metal"},
      {"k", ParamType::Spectrum, "1", nullptr,
       "extinction coefficient of a conductor's complex index, within [0, 1000]", "3.5", "metal"},
      {"metal", ParamType::Name, "-", nullptr,
       "a built-in metal's measured eta and k: gold, silver, copper, aluminium", "gold", "eta k"},
      differentiable({"alpha", ParamType::Number, "1", &kAlphaRange,
                      "isotropic GGX roughness alpha (0: smooth)", "0.2", "alpha_u alpha_v"}),
      differentiable({"alpha_u", ParamType::Number, "1", &kAlphaRange,
                      "GGX roughness along the surface tangent dpdu (with <alpha_v>)", "0.1",
                      "alpha"}),
      differentiable({"alpha_v", ParamType::Number, "1", &kAlphaRange,
                      "GGX roughness across the surface tangent (with <alpha_u>)", "0.3", "alpha"}),
      {"sigma", ParamType::Number, "0.5", &kOrenNayarRange,
       "rough diffuse roughness sigma in [0, 1] (Fujii's Oren-Nayar parameter; 0: Lambertian)",
       "0.3"},
      {"coating", ParamType::Coating, "nm", &kCoatingThicknessRange,
       "thin-film coating: <thickness> in nm and its <ior> (interference colours)",
       "<thickness>150</thickness><ior>1.4</ior>"},
  };
  return specs;
}

const ParamSpec* materialParameter(std::string_view name) {
  for (const ParamSpec& s : materialParameters())
    if (name == s.name) return &s;
  return nullptr;
}

} // namespace nx
