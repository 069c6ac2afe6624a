#pragma once
// The camera a scene describes: the look-at form as it always was, or OpenCV's calibration
// (either part may stand alone: intrinsics with a look-at pose, extrinsics with a field of
// view), with its distortion checked to map the image one to one, and an optional thin lens.

#include "core/camera.h"
#include "io/scene_desc.h"

namespace nx {

/// The camera of `c` for a width x height image; throws nx::Error with the camera's (or its
/// <distortion>'s) file:line when it cannot form that image (checkCameraDesc, folds).
PinholeCamera cameraFromDesc(const CameraDesc& c, int width, int height);

} // namespace nx
