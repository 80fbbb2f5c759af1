#pragma once
// The actions of `tessera-anaglyph --script FILE`: what a person would do
// at the window, one a line, for tests and demos (--help-script lists them).
#include <string>
#include <vector>

namespace tsr::app {

struct WindowAction {
  enum class Kind { Key, Orbit, Pan, Scroll, Frames, Screenshot } kind;
  std::string text;     // key name or screenshot path
  double x = 0, y = 0;  // drag pixels, wheel notches, frame count
};

// Throws std::invalid_argument "script FILE line N: ..." for an unknown
// action, a bad number or a NUL byte, and "FILE: ..." for a file that is
// missing, a folder, over 64 KiB or over 4096 actions.
std::vector<WindowAction> parseWindowScript(const std::string& path);
// The same for text already read; `name` stands for FILE.
std::vector<WindowAction> parseWindowScriptText(const std::string& text, const std::string& name);

}  // namespace tsr::app
