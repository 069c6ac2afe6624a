#include "io/relight_layers.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace nx {

RelightGrid RelightGrid::withStep(double stepNm) {
  RelightGrid g;
  g.stepNm = stepNm;
  g.bins = static_cast<int>(std::ceil((1100.0 - g.firstNm) / stepNm - 1e-9));
  return g;
}

void checkRelightStep(double stepNm, const std::string& option) {
  const auto whole = [](double x) { return std::abs(x - std::round(x)) < 1e-9 && x >= 1; };
  // From 0.1 nm (8000 bins over the traced range: a laser line's width) to 100 nm; 1e-6 built
  // for minutes at 12 GiB and 1e-300 overflowed the bin count.
  if (!(stepNm >= kMinRelightStepNm && stepNm <= 100 && (whole(5 / stepNm) || whole(stepNm / 5))))
    throw Error(option + ": expected a step in nm from " + numberText(kMinRelightStepNm) +
                " to 100 that divides 5 (0.1, 0.25, 0.5, 1, 2.5, 5) or is a multiple of 5 (its "
                "bins nest with the 5 nm re-radiation grid), found " +
                numberText(stepNm));
}

int RelightLayers::sourceIndex(const std::string& name) const {
  for (size_t i = 0; i < sources.size(); ++i)
    if (sources[i] == name) return static_cast<int>(i);
  return -1;
}

std::vector<std::string> RelightLayers::groups() const {
  std::vector<std::string> out;
  for (size_t s = 0; s < sources.size(); ++s)
    if (std::find(out.begin(), out.end(), groupOf(s)) == out.end()) out.push_back(groupOf(s));
  return out;
}

} // namespace nx
