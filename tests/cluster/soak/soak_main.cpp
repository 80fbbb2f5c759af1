// tsr_soak: the long soak of scripts/soak.sh. Runs soak_run.hpp's soak in
// the modes asked for, prints progress and each mode's report, and exits 1
// when replicas diverged, a fault did not recover, node memory or
// descriptors grew past the bounds, or frames slowed past --max-slowdown
// under hostile peers.
#include <CLI/CLI.hpp>

#include <iostream>

#include "soak/soak_run.hpp"

int main(int argc, char** argv) {
  using namespace tsr::cluster;
  using namespace tsr::cluster::test;
  CLI::App app{"Soak of four loopback tessera-node processes with injected faults"};
  int frames = 10000, hashEvery = 100;
  std::uint32_t size = 32;
  std::vector<std::string> modes{"cooperative", "tiled", "stereo"};
  std::string renderBinary;
  double maxSlowdown = 3.0, maxRssGrowthMiB = 32.0;
  bool noFaults = false;
  app.add_option("--frames", frames, "frames per mode (default 10000)")->check(CLI::Range(10, 10000000));
  app.add_option("--hash-every", hashEvery, "replica hash check every N frames (default 100)")
      ->check(CLI::Range(1, 1000000));
  app.add_option("--size", size, "image side in pixels (default 32)")->check(CLI::Range(8, 1024));
  app.add_option("--modes", modes, "cluster modes (default: cooperative tiled stereo)")
      ->check(CLI::IsMember({"cooperative", "tiled", "stereo"}));
  app.add_option("--render-binary", renderBinary, "tessera-render, for the killed-client fault (none: left out)")
      ->check(CLI::ExistingFile);
  app.add_option("--max-slowdown", maxSlowdown,
                 "allowed median frame time under garbage peers over the baseline (default 3)")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-rss-growth-mib", maxRssGrowthMiB,
                 "allowed growth of a node's RSS from start to end (default 32)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--no-faults", noFaults, "soak only, no faults");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }
  bool ok = true;
  for (const auto& name : modes) {
    SoakOptions o;
    o.mode = name == "tiled" ? ClusterMode::Tiled : name == "stereo" ? ClusterMode::Stereo : ClusterMode::Cooperative;
    o.frames = frames;
    o.hashEvery = hashEvery;
    o.size = size;
    o.faults = !noFaults;
    o.renderBinary = renderBinary;
    o.log = [](const std::string& line) { std::cerr << line << std::endl; };
    SoakReport r;
    try {
      r = runSoak(o);
    } catch (const std::exception& e) {
      std::cerr << "error: " << name << ": " << e.what() << "\n";
      return 1;
    }
    std::cout << name << ": " << describe(r) << std::flush;
    auto fail = [&](const std::string& why) {
      std::cout << name << ": FAIL: " << why << "\n";
      ok = false;
    };
    if (r.divergences) fail(std::to_string(r.divergences) + " divergent replicas");
    if (r.failedFrames) fail(std::to_string(r.failedFrames) + " frames failed");
    for (const auto& f : r.faults) {
      if (f.recoverySeconds < 0) fail(f.name + " never recovered");
      if (f.detail.find("FAILED") != std::string::npos || f.detail.find("NOT") != std::string::npos)
        fail(f.name + ": " + f.detail);
      if (f.name.rfind("garbage", 0) == 0 && f.frameSlowdown > maxSlowdown)
        fail("frames slowed x" + std::to_string(f.frameSlowdown) + " under garbage peers (bound x" +
             std::to_string(maxSlowdown) + ")");
    }
    for (std::size_t i = 0; i < r.start.size() && i < r.end.size(); ++i) {
      if (r.end[i].rssKiB > r.start[i].rssKiB + static_cast<long>(maxRssGrowthMiB * 1024))
        fail("node " + std::to_string(i) + " RSS grew past the bound");
      if (r.end[i].fds > r.start[i].fds + 4) fail("node " + std::to_string(i) + " holds more descriptors");
    }
  }
  std::cout << (ok ? "soak: PASS" : "soak: FAIL") << "\n";
  return ok ? 0 : 1;
}
