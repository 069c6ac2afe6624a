#include "io/camera_attributes.h"

#include <initializer_list>

#include "core/error.h"

namespace nx {
namespace {
std::string numbers(std::initializer_list<double> values) {
  std::string out;
  for (double v : values) {
    if (!out.empty()) out += ',';
    out += exactNumberText(v);
  }
  return out;
}
} // namespace

std::map<std::string, std::string> cameraAttributes(const PinholeCamera& camera) {
  const CameraCalibration& c = camera.calibration();
  const Matrix3& R = c.R;
  const std::array<double, 5>& d = c.distortion;
  std::map<std::string, std::string> a{
      {"nxrender.camera.K", numbers({c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1})},
      {"nxrender.camera.R",
       numbers({R[0][0], R[0][1], R[0][2], R[1][0], R[1][1], R[1][2], R[2][0], R[2][1], R[2][2]})},
      {"nxrender.camera.t", numbers({c.t.x, c.t.y, c.t.z})},
      {"nxrender.camera.distortion", numbers({d[0], d[1], d[2], d[3], d[4]})},
      {"nxrender.camera.worldToCamera",
       numbers({R[0][0], R[0][1], R[0][2], c.t.x, R[1][0], R[1][1], R[1][2], c.t.y, R[2][0],
                R[2][1], R[2][2], c.t.z, 0, 0, 0, 1})},
  };
  if (camera.hasLens())
    a["nxrender.camera.thinLens"] = numbers({camera.lensRadius(), camera.focusDistance()});
  return a;
}

} // namespace nx
