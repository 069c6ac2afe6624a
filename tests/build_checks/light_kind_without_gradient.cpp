// Must not compile: a light kind the gradient code does not declare (LightGradient) is a
// compile error, not a std::bad_variant_access at run time (tests/build_checks/expect_error.sh).

#include "integrators/gradients/light_gradients.h"

namespace {
struct NewLight {
  int anything = 0;
};
} // namespace

int main() {
  const NewLight light;
  return nx::LightGradient<NewLight>::spectrum(light) == nullptr;
}
