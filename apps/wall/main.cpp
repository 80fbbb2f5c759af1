// tessera-wall CONFIG SCENE [--nodes A,B,...] [--token-file F] [--frames N] [--spp N] [--fps F]
//              [--size WxH] [--max-fps F] [--status-every S] [--output FILE]
// Plays a scene's animation on a display wall (Schwenk 5.3.4): each node of
// the config renders its screen and presents it when the swap barrier
// releases the frame. Prints the frame rate and every node's status; a
// node that drops out has its tile marked and is taken back when it
// returns; a late node is named with its phase and since when.
// Errors: one "error:" line on stderr, exit status 2.
#include <array>
#include <atomic>
#include <csignal>
#include <iostream>
#include <optional>
#include <sstream>
#include <thread>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include "backends.hpp"
#include "command_line.hpp"
#include "error_line.hpp"
#include "import_limit_options.hpp"
#include "option_values.hpp"
#include "preview_defaults.hpp"
#include "render_job.hpp"
#include "scene/scene_session.hpp"
#include "tsr/cluster/auth.hpp"
#include "tsr/cluster/cluster_window.hpp"
#include "tsr/cluster/workload.hpp"
#include "tsr/med/file_replacement.hpp"
#include "tsr/med/image_file.hpp"
#include "tsr/sg/import/importer.hpp"

namespace {

std::atomic<bool> interrupted{false};

using tsr::cluster::NodeState;
using Clock = std::chrono::steady_clock;

struct Options {
  std::string config, scene, nodes, tokenFile, size, output, camera;
  std::optional<double> aperture, fNumber, focusDistance;  // the camera's lens, when given
  std::string shutter;                                     // OPEN,CLOSE, when given
  bool seedPerFrame = false;                               // --seed-per-frame
  std::vector<std::string> params;                         // --param name=value, for every node whose back-end takes it
  tsr::sg::ImportOptions import;
  std::uint64_t frames = 0;  // 0: until interrupted
  std::int64_t spp = 0;      // 0: the config's
  double fps = 24.0;
  double maxFps = 0.0;  // 0: as fast as the nodes go
  double statusEvery = 1.0;
  bool pixelsBack = false;
  std::string workload = "off";  // off, beside, over
};

const char* stateName(NodeState s) {
  // In NodeState's order. The assert catches a table out of step with the
  // enumerators up to the last one named there; a state appended after it
  // needs its name here and the assert moved to it.
  static constexpr std::array kNames{"OFFLINE", "connecting", "joined", "ok"};
  static_assert(kNames.size() == std::size_t(NodeState::Synced) + 1);
  return std::size_t(s) < kNames.size() ? kNames[std::size_t(s)] : "?";
}

std::string statusLine(const tsr::cluster::ClusterWindow& wall, std::uint64_t frame, double fps,
                       const tsr::cluster::ClusterFrame& last) {
  std::ostringstream out;
  out << "frame " << frame << "  " << std::fixed;
  out.precision(1);
  out << fps << " fps";
  if (last.offlineTiles) out << "  " << last.offlineTiles << " tile(s) marked offline";
  auto status = wall.status();
  for (std::size_t i = 0; i < status.size(); ++i) {
    const auto& s = status[i];
    out << "\n  screen " << i << "  " << s.address.text() << " " << (s.name.empty() ? "?" : s.name) << "  "
        << stateName(s.state);
    if (s.state != NodeState::Synced) {
      auto ago = std::chrono::duration<double>(Clock::now() - s.phaseSince).count();
      out << " for " << ago << " s (" << tsr::cluster::name(s.phase) << ")";
      if (!s.lastError.empty()) out << ": " << s.lastError;
    } else if (i < last.busySeconds.size()) {
      out.precision(3);
      out << "  busy " << last.busySeconds[i] << " s";
      out.precision(1);
    }
  }
  return out.str();
}

// --workload: each screen's share of the last frame, and its balance.
std::string workloadLine(const tsr::cluster::ClusterWindow& wall) {
  const tsr::cluster::FrameWorkload& w = wall.lastWorkload();
  std::ostringstream out;
  out << std::fixed;
  out.precision(2);
  out << "  workload: balance " << w.balance << " (slowest screen's render time over the mean)";
  for (std::size_t i = 0; i < w.nodes.size(); ++i) {
    out.precision(1);
    out << "\n    screen " << i << "  " << w.nodes[i].pixels << " px  " << w.nodes[i].seconds * 1e3 << " ms";
  }
  return out.str();
}

// The stitched frame with the workload image over it, half and half.
tsr::med::FrameBuffer withWorkloadOver(tsr::med::FrameBuffer frame) {
  const auto it = frame.outputs.find(std::string(tsr::cluster::kWorkloadOutput));
  if (it == frame.outputs.end()) return frame;
  for (std::size_t i = 0; i < frame.colour.size(); ++i)
    frame.colour[i] = glm::vec4(glm::mix(glm::vec3(frame.colour[i]), glm::vec3(it->second[i]), 0.5f), 1.0f);
  return frame;
}

// The cluster config as the wall runs it: tiled, with --nodes' addresses,
// --spp, --seed-per-frame, the preview filter and --param applied, validated.
tsr::cluster::ClusterConfig wallConfig(const Options& o) {
  tsr::cluster::ClusterConfig config = tsr::cluster::loadClusterConfig(o.config);
  if (config.mode != tsr::cluster::ClusterMode::Tiled)
    throw std::invalid_argument(o.config + ": a wall needs \"mode\": \"tiled\"");
  if (!o.nodes.empty()) config.replaceAddresses(tsr::cluster::parseNodeList(o.nodes));
  const tsr::med::ViewportRegistry& registry = tsr::app::backendRegistry();
  for (auto& n : config.nodes) {
    if (!registry.has(n.backend)) continue;  // config.validate names it
    const tsr::med::ParameterTable& table = registry.capabilities(n.backend).parameters;
    if (o.spp > 0 && table.declares("spp")) n.parameters.set("spp", o.spp);
    if (o.seedPerFrame && table.declares("seedPerFrame")) n.parameters.set("seedPerFrame", true);
    tsr::app::usePreviewDefaultsUnlessSet(n.parameters, &table);
  }
  for (const std::string& p : o.params) {
    auto [name, value] = tsr::med::Parameters::parse(p);
    bool taken = false;
    for (auto& n : config.nodes) {
      if (!registry.has(n.backend) || !registry.capabilities(n.backend).parameters.declares(name)) continue;
      registry.capabilities(n.backend).parameters.validate(name, value);
      n.parameters.set(name, value);
      taken = true;
    }
    if (!taken) throw std::invalid_argument("--param " + p + ": no node's back-end takes '" + name + "'");
  }
  if (!config.nodes.empty()) std::cout << tsr::app::previewDefaultsLine(config.nodes.front().parameters) << std::endl;
  config.validate();
  return config;
}

// The client's cost per frame after the first (which carries the snapshots).
struct Totals {
  std::uint64_t frames = 0, sent = 0, received = 0;
  double seconds = 0, assemble = 0, barrier = 0;

  void report() const {
    if (frames > 0) {
      double n = static_cast<double>(frames);
      std::cout << std::fixed;
      std::cout.precision(3);
      std::cout << "client per frame (" << frames << " frames after the first): " << 1e3 * seconds / n << " ms in all, "
                << 1e3 * assemble / n << " ms assembling tiles, " << 1e3 * barrier / n << " ms barrier spread, "
                << static_cast<double>(sent) / n << " bytes sent, " << static_cast<double>(received) / n
                << " bytes received" << std::endl;
    }
  }
};

// Says which nodes dropped out since the frame before and which came back.
void reportNodeChanges(const std::vector<tsr::cluster::NodeStatus>& status, std::vector<NodeState>& before,
                       std::uint64_t frame) {
  for (std::size_t i = 0; i < status.size(); ++i) {
    bool wasIn = before[i] == NodeState::Synced, isIn = status[i].state == NodeState::Synced;
    if (wasIn && !isIn)
      std::cout << "node " << status[i].address.text() << " dropped out (" << status[i].lastError << "): screen " << i
                << " marked offline" << std::endl;
    if (!wasIn && isIn && frame > 0)
      std::cout << "node " << status[i].address.text() << " is back on screen " << i << std::endl;
    before[i] = status[i].state;
  }
}

// --output: the last frame (with the workload over or beside it).
void writeOutputs(const Options& o, const tsr::cluster::ClusterFrame& last) {
  if (!o.output.empty() && last.image.width > 0) {
    const tsr::med::FrameBuffer& shown = o.workload == "over" ? withWorkloadOver(last.image) : last.image;
    tsr::med::replaceFile(o.output, [&](const std::string& temporary) { tsr::med::writeImage(temporary, shown); });
    std::cout << "wrote " << o.output << std::endl;
    if (o.workload == "beside") {
      const std::string beside = tsr::app::aovPath(o.output, std::string(tsr::cluster::kWorkloadOutput));
      tsr::med::replaceFile(beside, [&](const std::string& temporary) {
        tsr::med::writeImage(temporary, last.image, std::string(tsr::cluster::kWorkloadOutput));
      });
      std::cout << "wrote " << beside << std::endl;
    }
  }
}

int run(const Options& o) {
  tsr::cluster::ClusterConfig config = wallConfig(o);
  std::uint32_t width = config.wall.frameWidth ? config.wall.frameWidth : 960;
  std::uint32_t height = config.wall.frameHeight ? config.wall.frameHeight : 540;
  if (!o.size.empty()) tsr::app::parseSize(o.size, width, height);

  tsr::app::SceneSession session;
  tsr::app::ViewChoice view;
  view.camera = o.camera;
  if (o.aperture) view.look.apertureRadius = float(*o.aperture);
  if (o.fNumber) view.look.fNumber = float(*o.fNumber);
  if (o.focusDistance) view.look.focusDistance = float(*o.focusDistance);
  if (!o.shutter.empty()) view.look.shutter = tsr::app::parseShutter(o.shutter);
  session.load(o.scene, o.import, view);
  tsr::cluster::ClientOptions client;
  if (!o.tokenFile.empty()) client.token = tsr::cluster::readTokenFile(o.tokenFile);
  client.name = "tessera-wall";
  if (o.workload != "off") client.outputs.emplace_back(tsr::cluster::kWorkloadOutput);
  tsr::cluster::ClusterWindow wall(config, client);
  wall.setContent(session.imported.root, session.imported.background);
  std::size_t online = wall.connect(config.timeouts.connect);
  std::cout << online << " of " << config.nodes.size() << " nodes online; " << width << "x" << height << ", "
            << session.imported.animations.size() << " animation(s)" << std::endl;

  std::vector<NodeState> before(config.nodes.size(), NodeState::Offline);
  auto started = Clock::now(), lastStatus = started;
  std::uint64_t framesSinceStatus = 0;
  tsr::cluster::ClusterFrame last;
  Totals totals;
  auto bytes = [&] {
    std::pair<std::uint64_t, std::uint64_t> b{0, 0};
    for (const auto& s : wall.status()) {
      b.first += s.bytesSent;
      b.second += s.bytesReceived;
    }
    return b;
  };
  auto nextFrameAt = started;
  for (std::uint64_t frame = 0; (o.frames == 0 || frame < o.frames) && !interrupted; ++frame) {
    if (o.maxFps > 0) {
      std::this_thread::sleep_until(nextFrameAt);
      nextFrameAt = std::max(
          nextFrameAt + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / o.maxFps)),
          Clock::now() - std::chrono::seconds(1));
    }
    session.poseAnimations(static_cast<double>(frame) / o.fps, 1.0 / o.fps);
    auto frameStarted = Clock::now();
    auto bytesBefore = bytes();
    auto delta = session.publish();
    wall.publish(session.source, delta);
    const tsr::sg::Camera* camera = session.source.find<tsr::sg::Camera>(session.camera);
    // The nodes present their screens themselves: pixels travel to this
    // client only for the frame --output writes (with --frames 0, every one).
    wall.keepPixelsOnNodes(!o.pixelsBack && (o.output.empty() || (o.frames != 0 && frame + 1 != o.frames)));
    last = wall.render(tsr::med::View::fromCamera(*camera, width, height), static_cast<std::int64_t>(frame));
    ++framesSinceStatus;
    if (frame > 0) {
      auto bytesAfter = bytes();
      ++totals.frames;
      totals.seconds += std::chrono::duration<double>(Clock::now() - frameStarted).count();
      totals.assemble += last.assembleSeconds;
      totals.barrier += last.barrierSeconds;
      totals.sent += bytesAfter.first - bytesBefore.first;
      totals.received += bytesAfter.second - bytesBefore.second;
    }
    for (const auto& late : last.lateNodes) std::cout << "late: frame " << last.frame << ": " << late << std::endl;
    reportNodeChanges(wall.status(), before, frame);
    auto now = Clock::now();
    double since = std::chrono::duration<double>(now - lastStatus).count();
    bool lastFrame = o.frames != 0 && frame + 1 == o.frames;
    if (since >= o.statusEvery || lastFrame) {
      std::cout << statusLine(wall, last.frame, static_cast<double>(framesSinceStatus) / std::max(since, 1e-9), last)
                << (o.workload != "off" ? "\n" + workloadLine(wall) : std::string()) << std::endl;
      lastStatus = now;
      framesSinceStatus = 0;
    }
  }
  totals.report();
  writeOutputs(o, last);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Tessera display wall: plays a scene on the nodes of a tiled config, swapping their screens together"};
  Options o;
  std::string logLevel = "warn";
  app.add_option("CONFIG", o.config, "cluster config with \"mode\": \"tiled\" (a grid or screens, see configs/)")
      ->required();
  app.add_option("SCENE", o.scene, tsr::app::sceneArgumentHelp())->required();
  app.add_option("--nodes", o.nodes, "node addresses A:P,B:Q,... in screen order (default: the config's)");
  app.add_option("--token-file", o.tokenFile, "file holding the token the nodes were started with")
      ->check(tsr::app::FileName());
  app.add_option("--frames", o.frames, "frames to play (0: until interrupted)")->capture_default_str();
  app.add_option("--spp", o.spp, "samples per pixel on every node (0: the config's)")
      ->capture_default_str()
      ->check(CLI::Range(std::int64_t{0}, std::int64_t{1} << 20));
  app.add_option("--fps", o.fps, "animation frames per second of scene time")
      ->capture_default_str()
      ->check(tsr::app::FiniteRange(0.001, 1000.0));
  app.add_option("--max-fps", o.maxFps, "at most this many frames a second (0: as fast as the nodes render)")
      ->capture_default_str()
      ->check(tsr::app::FiniteRange(0.0, 1000.0));
  app.add_option("--size", o.size, "virtual frame WxH (default: the config's wall frame, else 960x540)");
  app.add_option("--status-every", o.statusEvery, "seconds between status lines")
      ->capture_default_str()
      ->check(tsr::app::FiniteRange(0.0, 3600.0));
  app.add_option("--camera", o.camera, "the scene camera to play through: its name or index (default: the first)");
  app.add_option("--aperture", o.aperture,
                 "thin lens radius in scene units: depth of field on path-tracing nodes (0: a pinhole)");
  app.add_option("--f-number", o.fNumber,
                 "the lens as an f-number instead of --aperture (radius = focal length / (2 N), the focal length a "
                 "full-frame camera has at this field of view, in metres converted to the scene's unit: glTF metres, "
                 "builtin:cornell millimetres)");
  app.add_option("--focus-distance", o.focusDistance, "distance in focus along the view, scene units");
  app.add_flag("--seed-per-frame", o.seedPerFrame,
               "each frame draws its own random numbers (seed + frame) on path-tracing nodes: the noise moves "
               "instead of sticking to the screen (default: one seed)");
  app.add_option("--shutter", o.shutter,
                 "OPEN,CLOSE as fractions of the frame interval: what the animation moves is blurred between, on "
                 "path-tracing nodes (default 0,0: an instant)");
  app.add_option(
         "--output", o.output,
         "write the last stitched frame here (PNG, EXR, ...); only that frame's pixels come back from the nodes")
      ->check(tsr::app::FileName());
  app.add_flag("--pixels-back", o.pixelsBack,
               "every frame's pixels come back to this client, as they would for a preview (default: they stay on "
               "the nodes, which present them)");
  app.add_option("--param", o.params,
                 "back-end parameter name=value for every node whose back-end takes it (repeatable), e.g. "
                 "visibility=guided");
  app.add_option("--workload", o.workload,
                 "which screen rendered what: off; beside (status lines give each screen's pixels and render time "
                 "and the balance, --output gets FILE.workload.EXT beside it: each screen in its node's colour, "
                 "darker the quicker); over (the same, drawn half over the --output frame)")
      ->capture_default_str()
      ->check(CLI::IsMember({"off", "beside", "over"}));
  app.add_option("--log-level", logLevel, "trace, debug, info, warn, error")->capture_default_str();
  tsr::app::ImportLimitOptions importLimits;
  importLimits.add(app, o.import);
  try {
    if (!tsr::app::parseCommandLine(app, argc, argv)) return 0;
    importLimits.apply(o.import);
    spdlog::set_default_logger(spdlog::stderr_color_mt("wall"));
    spdlog::set_level(spdlog::level::from_str(logLevel));
    std::signal(SIGINT, [](int) { interrupted = true; });
    std::signal(SIGTERM, [](int) { interrupted = true; });
    return run(o);
  } catch (const std::exception& e) {
    tsr::app::printError(e.what());
    return 2;
  }
}
