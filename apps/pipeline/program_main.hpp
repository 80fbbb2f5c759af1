#pragma once
// A program's main around its body: an error ends it with one line on
// stderr and exit status 2; a scene over an import limit names the option
// that raises it.
#include <string>

#include "error_line.hpp"
#include "option_values.hpp"

namespace tsr::app {

inline int runProgram(int (*run)(int, char**), int argc, char** argv) {
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
