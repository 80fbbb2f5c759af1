#include "window_script.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "text_file.hpp"

namespace tsr::app {

namespace {
constexpr std::uintmax_t kMaxScriptBytes = 64 * 1024;
constexpr std::size_t kMaxActions = 4096;
const std::string kKeys = "wasdqe[]-=mr";
}  // namespace

std::vector<WindowAction> parseWindowScript(const std::string& path) {
  return parseWindowScriptText(readTextFile<std::invalid_argument>(path, kMaxScriptBytes), path);
}

std::vector<WindowAction> parseWindowScriptText(const std::string& text, const std::string& path) {
  if (text.size() > kMaxScriptBytes) throw std::invalid_argument(path + ": larger than 64 KiB");
  std::istringstream in(text);
  std::vector<WindowAction> actions;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    auto fail = [&](const std::string& why) {
      throw std::invalid_argument("script " + path + " line " + std::to_string(number) + ": " + why);
    };
    if (line.find('\0') != std::string::npos) fail("a NUL byte (not a text file?)");
    if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::string verb;
    if (!(words >> verb)) continue;
    WindowAction a{WindowAction::Kind::Key, "", 0, 0};
    auto number2 = [&](double& v, double lo, double hi) {
      if (!(words >> v) || !std::isfinite(v) || v < lo || v > hi)
        fail(verb + " needs a number in " + std::to_string(int(lo)) + ".." + std::to_string(int(hi)));
    };
    if (verb == "key") {
      a.kind = WindowAction::Kind::Key;
      if (!(words >> a.text) || a.text.size() != 1 || kKeys.find(a.text[0]) == std::string::npos)
        fail("key needs one of: w a s d q e [ ] - = m r");
    } else if (verb == "orbit" || verb == "pan") {
      a.kind = verb == "orbit" ? WindowAction::Kind::Orbit : WindowAction::Kind::Pan;
      number2(a.x, -1e5, 1e5);
      number2(a.y, -1e5, 1e5);
    } else if (verb == "scroll") {
      a.kind = WindowAction::Kind::Scroll;
      number2(a.x, -1000, 1000);
    } else if (verb == "frames") {
      a.kind = WindowAction::Kind::Frames;
      number2(a.x, 1, 10000);
    } else if (verb == "screenshot") {
      a.kind = WindowAction::Kind::Screenshot;
      if (!(words >> a.text)) fail("screenshot needs a file name");
    } else {
      fail("unknown action '" + verb + "' (key, orbit, pan, scroll, frames, screenshot)");
    }
    std::string extra;
    if (words >> extra) fail("unexpected '" + extra + "' after " + verb);
    actions.push_back(std::move(a));
    if (actions.size() > kMaxActions) fail("more than 4096 actions");
  }
  return actions;
}

}  // namespace tsr::app
