#pragma once
// tessera-viewer's command line, parsed and checked; no window opened yet.
#include <cstdint>
#include <string>
#include <vector>

#include "tsr/med/parameters.hpp"
#include "tsr/sg/import/importer.hpp"

namespace tsr::app {

struct ViewerOptions {
  std::string scene = "builtin:cornell";
  std::vector<std::string> viewports{"embree"};  // one back-end per viewport, left to right
  std::uint32_t width = 1024, height = 576;      // the window
  std::uint32_t sampleLimit = 1024;              // the path tracer stops converging here
  bool rasterWhileMoving = false;                // figure 5.6: rasterise while the camera moves
  std::string script;                            // --script FILE
  bool exitAfter = false;                        // --exit-after: quit when the script is done
  bool hidePanels = false;
  bool validate = false;                  // Vulkan validation on the window's device; errors fail the run
  std::string cluster, nodes, tokenFile;  // --cluster CONFIG [--nodes A:P,...] [--token-file F]
  med::Parameters parameters;             // --max-depth, --threads, --param extras: every viewport
  sg::ImportOptions import;               // --max-file-mb, --max-elements
};

// The keys the window answers to, as --help lists them.
std::string viewerKeyHelp();

// Parses argv; throws std::invalid_argument with a one-line message. Returns
// false when help was printed (exit 0).
bool parseViewerOptions(int argc, char** argv, ViewerOptions& options);

}  // namespace tsr::app
