#pragma once
// The one exception type nxrender throws for bad input and failed I/O.

#include <stdexcept>
#include <string>

namespace nx {

/// A user-facing error: its message is complete ("file:line: expected ..., found ...").
class Error : public std::runtime_error {
public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

} // namespace nx
