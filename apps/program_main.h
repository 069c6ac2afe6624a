#pragma once
// The programs' entry point: run, and report an error as "<program>: error: <message>".

#include <cstdio>
#include <exception>

namespace nx {

/// Calls run(argc, argv) and returns its status; an exception it throws is printed to stderr
/// as "<program>: error: <what>" and gives status 1.
inline int mainReportingErrors(const char* program, int (*run)(int, char**), int argc,
                               char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    return 1;
  }
}

} // namespace nx
