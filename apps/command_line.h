#pragma once
// Command-line parsing shared by the programs: one range check that refuses NaN and names its
// bounds readably, and one way of reporting option errors ("<program>: error: ...", status 1
// or the program's usage status) instead of the option library's own codes (104-109).

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/error.h"
#include "core/input_files.h"
#include "core/number_text.h"

namespace nx {

/// A check that an option's value is a finite number within [lo, hi] (NaN and infinity are
/// refused, which CLI::Range let through): "expected a number from LO to HI, found 'X'".
inline CLI::Validator numberIn(double lo, double hi) {
  const std::string range = exactNumberText(lo) + " to " + exactNumberText(hi);
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        const char* end = nullptr;
        const double v = strtodC(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi)
          return "expected a number from " + range + ", found '" + text + "'";
        return "";
      },
      "in " + range);
}

/// Parses the command line. Returns -1 when the program should go on; otherwise the status to
/// exit with: 0 after --help, else `usageStatus` after printing "<program>: error: <message>".
/// Every floating-point option is checked to be finite, whether or not it has a range. From
/// here on, every file the program reads is recorded as an input that no output may replace
/// (core/input_files.h).
inline int parseCommandLine(CLI::App& app, int argc, char** argv, const char* program,
                            int usageStatus = 1) {
  recordInputFiles();
  // A repeatable option (a vector) takes one value per occurrence, never the words after it:
  // "--relight-for A --relight-for B scene.scn" had the scene taken as a third target.
  for (CLI::Option* option : app.get_options())
    if (!option->get_positional() && option->get_items_expected_max() > 1)
      option->allow_extra_args(false);
  try {
    app.parse(argc, argv);
    for (const CLI::Option* option : app.get_options()) {
      if (option->get_type_name().find("FLOAT") == std::string::npos) continue;
      for (const std::string& text : option->results()) {
        const double v = strtodC(text.c_str());
        if (!std::isfinite(v))
          throw CLI::ValidationError(option->get_name(),
                                     "expected a finite number, found '" + text + "'");
      }
    }
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "%s: error: %s\nRun with --help for more information.\n", program,
                 e.what());
    return usageStatus;
  }
  return -1;
}

} // namespace nx
