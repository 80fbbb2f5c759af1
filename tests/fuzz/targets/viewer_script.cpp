#include <string>

#include "fuzz_targets.hpp"
#include "viewer_script.hpp"

namespace tsr::fuzz {

// A --script file of a viewer with two viewports and every back-end.
void viewerScript(Bytes bytes) {
  const std::string text(bytes.begin(), bytes.end());
  const app::ScriptLimits limits{2, {"embree", "vulkan", "coverage"}};
  try {
    app::parseScriptText(text, "fuzz-input", limits);
  } catch (const app::ScriptError&) {}
}

}  // namespace tsr::fuzz
