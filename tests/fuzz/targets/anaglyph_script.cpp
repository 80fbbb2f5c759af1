#include <stdexcept>
#include <string>

#include "fuzz_targets.hpp"
#include "window_script.hpp"

namespace tsr::fuzz {

// tessera-anaglyph's --script file.
void anaglyphScript(Bytes bytes) {
  const std::string text(bytes.begin(), bytes.end());
  try {
    app::parseWindowScriptText(text, "fuzz-input");
  } catch (const std::invalid_argument&) {}
}

}  // namespace tsr::fuzz
