#include "sequence_options.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace tsr::app {

namespace {
double number(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(v)) throw std::invalid_argument(option + " " + text + ": not a number");
  return v;
}
}  // namespace

SequenceOptions parseSequenceOptions(const std::vector<std::string>& args) {
  SequenceOptions o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string arg = args[i], value;
    if (auto eq = arg.find('='); arg.rfind("--", 0) == 0 && eq != std::string::npos) {
      value = arg.substr(eq + 1);
      arg = arg.substr(0, eq);
    } else if (arg == "--frames" || arg == "--fps" || arg == "--cluster" || arg == "--nodes" || arg == "--token-file") {
      if (i + 1 >= args.size()) throw std::invalid_argument(arg + " needs a value");
      value = args[++i];
    }
    if (arg == "--frames") {
      double n = number(arg, value);
      if (n < 1 || n > 1e6 || n != std::floor(n)) throw std::invalid_argument("--frames must be a whole number 1..1000000");
      o.frames = static_cast<int>(n);
      o.framesGiven = true;
    } else if (arg == "--fps") {
      o.fps = number(arg, value);
      if (!(o.fps > 0)) throw std::invalid_argument("--fps must be positive");
    } else if (arg == "--cluster") {
      o.cluster = value;
    } else if (arg == "--nodes") {
      o.nodes = value;
    } else if (arg == "--token-file") {
      o.tokenFile = value;
    } else {
      throw std::invalid_argument("unknown argument " + args[i]);
    }
  }
  if (o.cluster.empty() && (!o.nodes.empty() || !o.tokenFile.empty()))
    throw std::invalid_argument("--nodes and --token-file need --cluster CONFIG.json");
  return o;
}

std::string framePath(const std::string& pattern, int frame) {
  auto at = pattern.find("####");
  if (at == std::string::npos) return pattern;
  char digits[16];
  std::snprintf(digits, sizeof digits, "%04d", frame);
  return pattern.substr(0, at) + digits + pattern.substr(at + 4);
}

}  // namespace tsr::app
