#pragma once
// tessera-anaglyph's command line, parsed and checked.
#include <cstdint>
#include <optional>
#include <string>

#include "tsr/med/compositing.hpp"
#include "tsr/med/parameters.hpp"
#include "tsr/sg/import/importer.hpp"

namespace tsr::app {

struct AnaglyphOptions {
  std::string scene;
  std::string backend = "embree";
  std::uint32_t width = 640, height = 480;
  med::Parameters parameters;  // spp, maxDepth, seed, threads
  med::AnaglyphMethod method = med::AnaglyphMethod::Dubois;
  std::optional<float> eyeSeparation, zeroParallax;  // unset: from the scene bounds (main.cpp)
  std::string nodes, tokenFile;                      // --nodes: eyes render on the nodes
  std::string output;                                // headless: one frame to this file
  std::string script;                                // window: actions from this file, then exit
  sg::ImportOptions import;
};

// Throws std::invalid_argument with a one-line message; false when help was printed.
bool parseAnaglyphOptions(int argc, char** argv, AnaglyphOptions& options);

const char* methodName(med::AnaglyphMethod method);

}  // namespace tsr::app
