#include "sequence/sequence_options.hpp"

#include <cstdio>

#include "command_line.hpp"

namespace tsr::app {

void addSequenceOptions(CLI::App& app, SequenceOptions& o) {
  auto* g = app.add_option_group("Sequences and clusters", "animations, and rendering through tessera-node processes");
  g->add_option("--frames", o.frames, "render N frames of the scene's animation (--output needs #### for the number)")
      ->check(CLI::Range(1, 1000000))
      ->each([&o](const std::string&) { o.framesGiven = true; });
  g->add_option("--fps", o.fps,
                "frames per second of animation time (default 24); with --shutter alone, one image's blur spans 1/fps")
      ->check(FinitePositive())
      ->each([&o](const std::string&) { o.fpsGiven = true; });
  auto* cluster = g->add_option("--cluster", o.cluster, "render on the nodes a cluster config names (configs/*.json)")
                      ->check(FileName());
  g->add_option("--nodes", o.nodes, "HOST:PORT,... replacing the config's node addresses in order")->needs(cluster);
  g->add_option("--token-file", o.tokenFile, "file holding the nodes' shared token")->check(FileName())->needs(cluster);
}

std::string framePath(const std::string& pattern, int frame) {
  auto at = pattern.find("####");
  if (at == std::string::npos) return pattern;
  char digits[16];
  std::snprintf(digits, sizeof digits, "%04d", frame);
  return pattern.substr(0, at) + digits + pattern.substr(at + 4);
}

}  // namespace tsr::app
