#include "apps/heightfield_scene.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/error.h"

namespace nx::bench {

void writeHeightfieldPly(const std::string& path, int n) {
  std::ofstream f(path, std::ios::binary);
  if (!f) throw nx::Error(path + ": cannot be written");
  const long long verts = static_cast<long long>(n + 1) * (n + 1), faces = 2LL * n * n;
  f << "ply\nformat binary_little_endian 1.0\nelement vertex " << verts
    << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << faces
    << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = static_cast<float>(-1 + 2.0 * i / n),
                  z = static_cast<float>(-1 + 2.0 * j / n);
      const float p[3] = {x, 0.1f * std::sin(8 * x) * std::cos(8 * z), z};
      f.write(reinterpret_cast<const char*>(p), sizeof p);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      const int tris[2][3] = {{a, b, c}, {a, c, d}};
      for (const auto& t : tris) {
        const unsigned char three = 3;
        f.write(reinterpret_cast<const char*>(&three), 1);
        f.write(reinterpret_cast<const char*>(t), sizeof t);
      }
    }
  if (!f) throw nx::Error(path + ": writing failed");
}

int heightfieldGridFor(long long triangles) {
  return std::max(1,
                  static_cast<int>(std::lround(std::sqrt(static_cast<double>(triangles) / 2.0))));
}

std::string heightfieldSceneXml(const std::string& plyFile, int width, int height, int spp,
                                const std::string& camera) {
  return "<scene><settings><xres>" + std::to_string(width) + "</xres><yres>" +
         std::to_string(height) + "</yres><mode>spectral_mcpt</mode><sampl>" + std::to_string(spp) +
         "</sampl></settings><camera><position>" + camera +
         "</position><look_at>0,0,0</look_at></camera><mesh file=\"" + plyFile +
         "\"><material>matte</material><reflectance>0.5</reflectance></mesh>"
         "<light><position>0,3,0</position><color>5,5,5</color></light></scene>";
}

} // namespace nx::bench
