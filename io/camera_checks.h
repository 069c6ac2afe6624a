#pragma once
// The checks a camera description must pass whichever way it was made (read from a scene file
// or edited from Python): one function, used by the scene build and by the Python setters.

#include "io/scene_desc.h"

namespace nx {

/// Largest magnitude of a distortion coefficient (<distortion>, calibration files, Python).
inline constexpr double kMaxDistortionCoefficient = 1e4;

/// Throws nx::Error "<camera's file:line>: expected ..., found ..." unless the camera can form
/// an image of width x height pixels: in the look-at form a look_at point apart from the
/// position and an up direction that is neither zero nor parallel to the view direction (the
/// image's axes were NaN, a black image); a field of view within kFovRange; intrinsics with
/// fx, fy in (0, 1e9], cx, cy within 1e7 pixels and fields of view a pinhole can have (at most
/// kFovRange's 179 degrees: fx of 1e-300 pixels rendered black); a thin lens of radius >= 0
/// focused at a positive distance; distortion coefficients within kMaxDistortionCoefficient.
void checkCameraDesc(const CameraDesc& camera, int width, int height);

/// What is wrong with extrinsics (R row by row, t) as "expected ..., found ..." text, or "":
/// R must be a rotation up to the rounding of printed calibration output (R^T R within 1e-4 of
/// the identity, determinant +1) and t within 1e12.
std::string extrinsicsProblem(const std::array<double, 12>& e);

} // namespace nx
