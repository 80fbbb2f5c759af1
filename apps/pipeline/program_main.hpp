#pragma once
// A program's main around its body: an error ends it with one line on
// stderr and exit status 2; a scene over an import limit names the option
// that raises it. SPDLOG_LEVEL in the environment (debug, info, ...) sets
// the log level over the program's own default.
#include <spdlog/cfg/env.h>

#include <string>

#include "error_line.hpp"
#include "option_values.hpp"

namespace tsr::app {

inline int runProgram(int (*run)(int, char**), int argc, char** argv) {
  spdlog::cfg::load_env_levels();
  try {
    return run(argc, argv);
  } catch (const sg::ImportLimitError& e) {
    printError(std::string(e.what()) + " (raise it with " + importLimitOption(e) + ")");
  } catch (const std::exception& e) {
    printError(e.what());
  }
  return 2;
}

}  // namespace tsr::app
