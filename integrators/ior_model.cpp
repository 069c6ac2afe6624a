#include "integrators/ior_model.h"

#include <cstring>

namespace nx {

bool namedGlass(const char* name, IorModel& out) {
  using K = IorModel::Kind;
  if (std::strcmp(name, "bk7") == 0) {
    out = {K::Sellmeier,
           {1.03961212, 0.231792344, 1.01046945, 0.00600069867, 0.0200179144, 103.560653}};
    return true;
  }
  if (std::strcmp(name, "diamond") == 0) {
    out = {K::Sellmeier, {0.3306, 4.3356, 0.0, 0.1750 * 0.1750, 0.1060 * 0.1060, 0.0}};
    return true;
  }
  if (std::strcmp(name, "fused_silica") == 0) {
    out = {K::Sellmeier,
           {0.6961663, 0.4079426, 0.8974794, 0.0684043 * 0.0684043, 0.1162414 * 0.1162414,
            9.896161 * 9.896161}};
    return true;
  }
  return false;
}

} // namespace nx
