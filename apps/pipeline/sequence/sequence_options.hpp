#pragma once
// tessera-render's frame-sequence and cluster options:
//   --frames N [--fps F]         N frames of the scene's animation
//   --cluster CONFIG.json        render through render nodes
//   [--nodes HOST:PORT,...]      replace the config's node addresses in order
//   [--token-file F]             the nodes' shared token
#include <CLI/CLI.hpp>

#include <string>

namespace tsr::app {

struct SequenceOptions {
  int frames = 1;
  double fps = 24.0;
  bool framesGiven = false;
  bool fpsGiven = false;
  std::string cluster;
  std::string nodes;
  std::string tokenFile;
  bool active() const { return framesGiven || !cluster.empty(); }
};

// Declares the options on `app` (so --help lists them), in their own group.
void addSequenceOptions(CLI::App& app, SequenceOptions& options);

// "out.####.png" + 7 -> "out.0007.png"; a name without #### is returned
// as is (a single frame).
std::string framePath(const std::string& pattern, int frame);

}  // namespace tsr::app
