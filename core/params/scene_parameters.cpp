#include "core/params/scene_parameters.h"

#include <stdexcept>

namespace nx {
namespace {

const FixedParameter kFixed[] = {
    {"resolution", "integers", "px", nullptr, "(width, height) in pixels"},
    {"mode", "name", "1", nullptr, "the rendering mode: rt, mcpt or spectral_mcpt"},
    {"spp", "integer", "1", nullptr, "samples per pixel"},
    {"seed", "integer", "1", nullptr, "the sampler's seed"},
    {"depth", "integer", "1", nullptr, "the bounce count"},
    {"bands", "text", "nm", nullptr, "the output bands ('400:700:10', 'gaussian:...', ...)"},
    {"background", "spectrum", "W m^-2 sr^-1 nm^-1", nullptr,
     "uniform environment radiance, or None (black)", true},
    {"illuminant", "spectrum", "1", nullptr, "the preview's white, or None (D65)"},
    {"path", "text", "", nullptr, "the output the command line writes (<path>)"},
    {"spectrum.value", "spectrum", "as used", nullptr,
     "a <spectrum name=...>'s values (its users' units)", true},
    {"camera.position", "point", "scene units", nullptr, "the eye (look-at form)", true},
    {"camera.look_at", "point", "scene units", nullptr, "the point looked at", true},
    {"camera.up", "vector", "1", nullptr, "the up direction"},
    {"camera.fov", "number", "degrees", &kFovRange, "horizontal field of view", true},
    {"camera.intrinsics", "numbers", "px", nullptr, "OpenCV fx, fy, cx, cy, or None"},
    {"camera.distortion", "numbers", "1", nullptr, "OpenCV k1, k2, p1, p2, k3"},
    {"camera.thin_lens", "numbers", "scene units", nullptr,
     "(aperture radius, focus distance), or None"},
    {"camera.extrinsics", "numbers", "1, scene units", nullptr,
     "OpenCV r11 .. r33, t1, t2, t3, or None", true},
    {"object.emission", "spectrum", "W m^-2 sr^-1 nm^-1", nullptr,
     "emitted radiance (an area light), or None", true},
    {"object.emission_scale", "number", "1", &kEmissionScaleRange,
     "the factor on its emission (0: switched off)", true},
    {"object.emission_at", "number", "scene units", &kMeasuredDistanceRange,
     "its emission is the irradiance on its axis at this distance (at=\"...\"), or None"},
    {"object.emission_quantity", "text", "-", nullptr,
     "what its emission gives: 'radiance' (default), 'flux' (total), or 'irradiance' (with "
     "emission_at)"},
    {"medium.dye_peak", "number", "1/scene unit", &kPeakCoefficientRange,
     "the dye's peak absorption coefficient", true},
    {"fluorescence.absorption_nm", "number", "nm", &kAbsorptionRange, "absorption peak", true},
    {"fluorescence.stokes_nm", "number", "nm", &kStokesRange, "Stokes shift", true},
    {"fluorescence.width_nm", "number", "nm", &kWidthRange, "band width (None: default)", true},
    {"fluorescence.skew", "number", "1", &kSkewRange, "band skew (None: default)", true},
    {"fluorescence.quantum_yield", "number", "1", &kYieldRange, "quantum yield (None: default)",
     true},
    {"fluorescence.peak_absorptance", "number", "1", &kPeakRange,
     "absorptance at the peak (None: default)", true},
    {"fluorescence.absorptance", "spectrum", "1", nullptr,
     "the dye's absorptance spectrum (the separable form; a medium's dye: its shape)", true},
    {"fluorescence.emission", "spectrum", "photons, any scale", nullptr,
     "the dye's emission spectrum (the separable form)", true},
    {"fluorescence.matrix", "matrix", "1", nullptr,
     "measured matrix (excitation_nm, emission_nm, values[excitation, emission])", true},
    {"fluorescence.concentration", "concentration map", "1", &kConcentrationRange,
     "the dye's relative concentration over the surface: values[height, width] in [0, 1] "
     "scaling its absorptance (row 0 at the top), or None (1 everywhere)",
     true},
};

} // namespace

std::span<const FixedParameter> fixedParameters() {
  return kFixed;
}

const FixedParameter& fixedParameter(const std::string& key) {
  for (const FixedParameter& f : kFixed)
    if (key == f.key) return f;
  throw std::logic_error("no parameter declaration '" + key + "'");
}

} // namespace nx
