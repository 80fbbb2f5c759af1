#pragma once
// Parses a program's command line the same way everywhere: --help prints
// the help and ends the program with success; any other CLI11 error becomes
// std::invalid_argument, which main() prints as one error line (exit 2)
// instead of CLI11's own several lines and exit codes of 105 and up.
#include <CLI/CLI.hpp>

#include <iostream>
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

}  // namespace tsr::app
