#pragma once
// The message a call fails with, for tests of error reporting.

#include <string>

#include "core/error.h"

namespace nx::test {

/// The what() of the nx::Error that f() throws, or "no error" if it returns.
template <typename F>
std::string errorMessage(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

} // namespace nx::test
