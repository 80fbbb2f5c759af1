#pragma once
// Parses a program's command line the same way everywhere: --help prints
// the help and ends the program with success; any other CLI11 error becomes
// std::invalid_argument, which main() prints as one error line (exit 2)
// instead of CLI11's own several lines and exit codes of 105 and up.
#include <CLI/CLI.hpp>

#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace tsr::app {

// False when --help was asked for (and printed): the caller stops there.
inline bool parseCommandLine(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return false;
  } catch (const CLI::ParseError& e) {
    throw std::invalid_argument(e.what());
  }
  return true;
}

// A file option given as "" (an unset shell variable, say) is refused: taken
// as not given, it would quietly change what the program does (no --output:
// a window; no --stats-json: no statistics).
inline CLI::Validator FileName() {
  return CLI::Validator(
      [](std::string& text) { return text.empty() ? std::string("an empty file name") : std::string(); }, "");
}

// A floating-point option's bounds. CLI::Range and CLI::PositiveNumber let
// "nan" through (every comparison with it is false) and PositiveNumber
// "inf": every real-valued option is checked with this instead.
inline CLI::Validator FiniteRange(double lo, double hi) {
  auto show = [](double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  };
  const std::string range = "[" + show(lo) + " - " + show(hi) + "]";
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v)) return "'" + text + "' is not a number";
        if (!std::isfinite(v) || v < lo || v > hi) return "value " + text + " not in range " + range;
        return {};
      },
      "FLOAT in " + range);
}
inline CLI::Validator FinitePositive() {
  return FiniteRange(std::numeric_limits<double>::min(), std::numeric_limits<double>::max());
}
inline CLI::Validator FiniteNonNegative() { return FiniteRange(0, std::numeric_limits<double>::max()); }

}  // namespace tsr::app
