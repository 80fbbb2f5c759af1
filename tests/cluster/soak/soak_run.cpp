#include "soak/soak_run.hpp"

#include <dirent.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>

#include "cluster_test_util.hpp"
#include "protocol/loopback_proxy.hpp"
#include "protocol/raw_client.hpp"
#include "tsr/cluster/cluster_window.hpp"
#include "tsr/cluster/handshake.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

extern char** environ;

namespace tsr::cluster::test {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
constexpr std::size_t kNodes = 4;
constexpr std::size_t kProxied = 3;  // this node is reached through the proxy
constexpr auto kDeadAfter = 1000ms;

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

NodeUsage usageOf(pid_t pid) {
  NodeUsage u;
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmRSS:", 0) == 0) u.rssKiB = std::stol(line.substr(6));
  if (DIR* d = opendir(("/proc/" + std::to_string(pid) + "/fd").c_str())) {
    while (dirent* e = readdir(d))
      if (e->d_name[0] != '.') ++u.fds;
    closedir(d);
  }
  return u;
}

med::Parameters pathTracer() {
  med::Parameters p;
  p.set("spp", std::int64_t{1});
  p.set("maxDepth", std::int64_t{2});
  p.set("seed", std::int64_t{3});
  p.set("threads", std::int64_t{1});
  return p;
}

// Every hostile peer of the issue, against every node, on a thread of its own.
void hostilePeers(const std::vector<NodeAddress>& targets, std::atomic<bool>& stop, std::string& detail) {
  std::mt19937 rng(17);
  int randomClosed = 0, absurdClosed = 0, lorisClosed = 0, floodConnected = 0;
  for (const auto& t : targets) {  // random bytes
    RawClient raw(t, 3000);
    std::vector<std::uint8_t> junk(4096);
    for (auto& b : junk) b = static_cast<std::uint8_t>(rng());
    raw.send(junk);
    randomClosed += raw.waitClosed() == RawClient::Outcome::Closed;
  }
  for (const auto& t : targets) {  // a valid header announcing a gigabyte
    RawClient raw(t, 3000);
    std::vector<std::uint8_t> header;
    writeFrameHeader(header, {kProtocolVersion, Hello::kType, 1u << 30});
    raw.send(header);
    absurdClosed += raw.waitClosed() == RawClient::Outcome::Closed;
  }
  {  // slow-loris: a Hello one byte a second, past the node's handshake timeout
    std::vector<std::unique_ptr<RawClient>> loris;
    for (const auto& t : targets) loris.push_back(std::make_unique<RawClient>(t, 1000));
    ClientHandshake hs("", "loris");
    const std::vector<std::uint8_t> hello = *hs.hello();
    std::vector<bool> open(loris.size(), true);
    for (std::size_t i = 0; i < hello.size() && i < 8 && !stop; ++i) {
      for (std::size_t n = 0; n < loris.size(); ++n)
        if (open[n]) open[n] = loris[n]->send(std::vector<std::uint8_t>{hello[i]});
      std::this_thread::sleep_for(1s);
    }
    for (auto& l : loris) lorisClosed += l->waitClosed() == RawClient::Outcome::Closed;
  }
  {  // 1,000 connections at once, spread over the nodes, held a second
    std::vector<std::unique_ptr<RawClient>> flood;
    for (int i = 0; i < 1000; ++i) {
      try {
        flood.push_back(std::make_unique<RawClient>(targets[i % targets.size()], 1000));
        ++floodConnected;
      } catch (const std::exception&) {}
    }
    std::this_thread::sleep_for(1s);
  }
  detail = "random bytes closed " + std::to_string(randomClosed) + "/" + std::to_string(targets.size()) +
           ", absurd length closed " + std::to_string(absurdClosed) + "/" + std::to_string(targets.size()) +
           ", slow-loris closed " + std::to_string(lorisClosed) + "/" + std::to_string(targets.size()) +
           ", flood connected " + std::to_string(floodConnected) + "/1000";
}

// A second client (tessera-render on the same nodes), started and killed.
pid_t spawnRender(const std::string& binary, const std::vector<std::string>& args) {
  std::vector<std::string> all{binary};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addclosefrom_np(&actions, STDERR_FILENO + 1);  // none of the soak's sockets
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start " + binary);
  return pid;
}

class Soak {
 public:
  explicit Soak(const SoakOptions& o) : o_(o) {
    nodes_ = startNodes(kNodes, {"--threads", "1"});
    proxy_ = std::make_unique<LoopbackProxy>(nodes_[kProxied]->address());
    ClusterConfig c = configFor(o.mode, nodes_, pathTracer());
    c.nodes[kProxied].address = proxy_->address();
    c.cooperative.tileSize = 8;
    c.timeouts.deadAfter = kDeadAfter;
    c.timeouts.heartbeat = 100ms;
    c.timeouts.frame = 20s;
    window_ = std::make_unique<ClusterWindow>(c);
    window_->setContent(scene_.imported.root, scene_.imported.background);
    if (window_->connect(10s) != kNodes) throw std::runtime_error("not every node joined");
  }

  SoakReport run() {
    const int n = o_.frames;
    // Faults at fixed points of the run, one after the other; each renders
    // frames until it is over and the cluster recovered.
    std::vector<std::pair<int, std::function<void()>>> faults;
    if (o_.faults) {
      faults = {{n * 15 / 100, [&] { killAndRestart(); }},
                {n * 27 / 100, [&] { stopAndResume(); }},
                {n * 39 / 100, [&] { cutMidSnapshot(); }},
                {n * 63 / 100, [&] { slowLink(); }},
                {n * 75 / 100, [&] { garbagePeers(); }}};
      if (!o_.renderBinary.empty()) faults.insert(faults.begin() + 3, {n * 51 / 100, [&] { killAClient(); }});
    }
    std::size_t nextFault = 0;
    int nextHash = o_.hashEvery;
    while (frame_ < n) {
      while (nextFault < faults.size() && frame_ >= faults[nextFault].first) {
        faulted_ = true;
        faults[nextFault++].second();
      }
      if (frame_ >= n) break;
      step();
      if (frame_ == 0)
        for (const auto& node : nodes_) report_.start.push_back(usageOf(node->pid()));
      ++frame_;
      if (frame_ >= nextHash) {
        checkHashes();
        nextHash = frame_ + o_.hashEvery;
      }
      if (o_.log && frame_ % 500 == 0)
        o_.log(modeName(o_.mode) + ": frame " + std::to_string(frame_) + "/" + std::to_string(n) + ", " +
               std::to_string(window_->onlineNodes()) + " nodes online");
    }
    checkHashes();
    for (const auto& node : nodes_) report_.end.push_back(usageOf(node->pid()));
    report_.baselineFrameSeconds = baseline();
    return report_;
  }

 private:
  struct Step {
    double seconds = 0;
    ClusterFrame frame;
    bool failed = false;
  };

  Step step() {
    scene_.pose(frame_ % 96);
    auto delta = scene_.scene.commit();
    const auto t0 = Clock::now();
    window_->publish(scene_.scene, delta);
    Step s;
    const sg::Camera* cam =
        scene_.imported.cameras.empty() ? nullptr : scene_.scene.find<sg::Camera>(scene_.imported.cameras.front());
    const sg::Camera fallback;
    const med::View view = med::View::fromCamera(cam ? *cam : fallback, o_.size, o_.size);
    try {
      s.frame = window_->render(view);
    } catch (const ClusterError&) {
      s.failed = true;
      ++report_.failedFrames;
    }
    s.seconds = seconds(Clock::now() - t0);
    ++report_.frames;
    if (!faulted_) baselineTimes_.push_back(s.seconds);
    if (report_.frames % 10 == 0) samplePeak();
    return s;
  }

  double baseline() const { return median(baselineTimes_); }

  void samplePeak() {
    for (const auto& node : nodes_)
      if (node->alive()) report_.peakRssKiB = std::max(report_.peakRssKiB, usageOf(node->pid()).rssKiB);
  }

  bool allSynced() const {
    auto st = window_->status();
    return std::all_of(st.begin(), st.end(), [](const NodeStatus& s) { return s.state == NodeState::Synced; });
  }

  void checkHashes() {
    if (!window_->waitApplied(scene_.scene.version(), 20s)) ++report_.divergences;
    ++report_.hashChecks;
    for (const auto& h : window_->replicaHashes(20s)) {
      ++report_.nodesChecked;
      if (h.version != scene_.scene.version() || h.hash != scene_.scene.contentHash()) ++report_.divergences;
    }
  }

  // Renders frames while `during` holds, then until every node is synced
  // and a frame has all its tiles (recovery); fills the outcome.
  void renderThrough(FaultOutcome& f, const std::function<bool()>& during, Clock::time_point* faultEnd = nullptr) {
    faulted_ = true;
    std::vector<double> times;
    auto account = [&](const Step& s) {
      ++f.framesAffected;
      f.offlineTiles += s.frame.offlineTiles;
      f.reassignedItems += s.frame.reassignedItems;
      f.failedFrames += s.failed;
      times.push_back(s.seconds);
      ++frame_;
    };
    while (during()) account(step());  // a fault always ends, even past the frames asked for
    const auto end = faultEnd ? *faultEnd : Clock::now();
    const auto limit = Clock::now() + 60s;
    while (Clock::now() < limit) {
      Step s = step();
      account(s);
      if (allSynced() && !s.failed && s.frame.offlineTiles == 0) {
        f.recoverySeconds = seconds(Clock::now() - end);
        break;
      }
      std::this_thread::sleep_for(10ms);
    }
    f.frameSlowdown = baseline() > 0 ? median(times) / baseline() : 0;
    report_.faults.push_back(f);
    checkHashes();  // every replica equal again after each fault
    if (o_.log) o_.log(modeName(o_.mode) + ": " + f.name + " recovered in " + std::to_string(f.recoverySeconds) + " s");
  }

  void killAndRestart() {
    FaultOutcome f;
    f.name = "node killed and restarted";
    const std::string address = nodes_[1]->text();
    nodes_[1]->kill();
    int frames = 0;
    auto restartedAt = Clock::now();
    renderThrough(
        f,
        [&] {
          if (++frames <= 5) return true;
          nodes_[1] = std::make_unique<NodeProcess>(std::vector<std::string>{"--threads", "1"}, address);
          restartedAt = Clock::now();
          return false;
        },
        &restartedAt);
  }

  void stopAndResume() {
    FaultOutcome f;
    f.name = "node stopped (SIGSTOP) past the dead-node timeout, resumed";
    nodes_[2]->pause();
    const auto resumeAt = Clock::now() + kDeadAfter * 2;
    auto resumed = resumeAt;
    renderThrough(
        f,
        [&] {
          if (Clock::now() < resumeAt) return true;
          nodes_[2]->resume();
          resumed = Clock::now();
          return false;
        },
        &resumed);
  }

  void cutMidSnapshot() {
    FaultOutcome f;
    f.name = "connection cut mid-snapshot";
    // The rejoin's handshake carries a few hundred bytes, then the
    // snapshot: the cut lands inside it.
    const std::size_t snapshot = sg::encode(*scene_.scene.snapshot()).size();
    const std::uint64_t before = proxy_->cuts();
    proxy_->cutNextAfter(256 + snapshot / 2);
    proxy_->cutAll();
    auto end = Clock::now();
    renderThrough(
        f,
        [&] {
          if (proxy_->cuts() > before) {
            end = Clock::now();
            return false;
          }
          return Clock::now() - end < 10s;
        },
        &end);
    f.detail = "snapshot " + std::to_string(snapshot) + " bytes, cut " +
               (proxy_->cuts() > before ? "inside it" : "NOT reached (rejoin without a snapshot?)");
    report_.faults.back().detail = f.detail;
  }

  void killAClient() {
    FaultOutcome f;
    f.name = "second client killed mid-frame";
    const std::string dir = std::filesystem::temp_directory_path() / ("tsr-soak-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    std::string addresses;
    for (std::size_t i = 0; i < kNodes; ++i) addresses += (i ? "," : "") + nodes_[i]->text();
    const std::string config = dir + "/wall.json";
    std::ofstream(config) << R"({"mode": "tiled", "backend": "embree",
      "parameters": {"spp": 4, "maxDepth": 2, "threads": 1}, "nodes": [
      {"address": "127.0.0.1:1"}, {"address": "127.0.0.1:2"}, {"address": "127.0.0.1:3"}, {"address": "127.0.0.1:4"}],
      "wall": {"columns": 2, "rows": 2}})";
    auto args = [&](int frames) {
      return std::vector<std::string>{"builtin:animated",
                                      "--cluster",
                                      config,
                                      "--nodes",
                                      addresses,
                                      "--size",
                                      "64x64",
                                      "--frames",
                                      std::to_string(frames),
                                      "--output",
                                      dir + "/f-####.png"};
    };
    const pid_t victim = spawnRender(o_.renderBinary, args(100000));
    // Killed once it has rendered a frame, so that it dies in the middle of a later one.
    const auto give = Clock::now() + 30s;
    while (Clock::now() < give && !std::filesystem::exists(dir + "/f-0001.png")) {
      step();
      ++frame_;
    }
    kill(victim, SIGKILL);
    waitpid(victim, nullptr, 0);
    auto killedAt = Clock::now();
    // The next client is served: a short render must succeed.
    const pid_t next = spawnRender(o_.renderBinary, args(2));
    int status = -1;
    renderThrough(
        f, [&] { return waitpid(next, &status, WNOHANG) == 0; }, &killedAt);
    f.detail = std::string("next client ") + (WIFEXITED(status) && WEXITSTATUS(status) == 0 ? "served" : "FAILED") +
               " (exit " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")";
    report_.faults.back().detail = f.detail;
    std::filesystem::remove_all(dir);
  }

  void slowLink() {
    FaultOutcome f;
    f.name = "slow link (16 KiB/s each way through the proxy)";
    proxy_->setRate(16 * 1024);
    const auto until = Clock::now() + 3s;
    auto end = until;
    renderThrough(
        f,
        [&] {
          if (Clock::now() < until) return true;
          proxy_->setRate(0);
          end = Clock::now();
          return false;
        },
        &end);
  }

  void garbagePeers() {
    FaultOutcome f;
    f.name = "garbage peers (random bytes, absurd length, slow-loris, 1,000 connections)";
    std::vector<NodeAddress> targets;
    for (const auto& node : nodes_) targets.push_back(node->address());
    std::atomic<bool> stop{false};
    std::atomic<bool> done{false};
    std::string detail;
    std::thread peers([&] {
      hostilePeers(targets, stop, detail);
      done = true;
    });
    auto end = Clock::now();
    renderThrough(
        f,
        [&] {
          samplePeak();
          if (!done) return true;
          end = Clock::now();
          return false;
        },
        &end);
    stop = true;
    peers.join();
    report_.faults.back().detail = detail;
  }

  SoakOptions o_;
  AnimatedScene scene_;
  std::vector<std::unique_ptr<NodeProcess>> nodes_;
  std::unique_ptr<LoopbackProxy> proxy_;
  std::unique_ptr<ClusterWindow> window_;
  SoakReport report_;
  std::vector<double> baselineTimes_;
  bool faulted_ = false;
  int frame_ = 0;
};

}  // namespace

std::string modeName(ClusterMode mode) {
  switch (mode) {
    case ClusterMode::Cooperative:
      return "cooperative";
    case ClusterMode::Tiled:
      return "tiled";
    case ClusterMode::Stereo:
      return "stereo";
  }
  return "?";
}

SoakReport runSoak(const SoakOptions& options) { return Soak(options).run(); }

std::string describe(const SoakReport& r) {
  std::ostringstream s;
  s << r.frames << " frames, " << r.failedFrames << " failed; " << r.hashChecks << " hash checks over "
    << r.nodesChecked << " replicas, " << r.divergences << " divergent; baseline " << r.baselineFrameSeconds * 1000
    << " ms/frame; peak node RSS " << r.peakRssKiB / 1024 << " MiB\n";
  for (std::size_t i = 0; i < r.start.size() && i < r.end.size(); ++i)
    s << "  node " << i << ": RSS " << r.start[i].rssKiB / 1024 << " -> " << r.end[i].rssKiB / 1024 << " MiB, fds "
      << r.start[i].fds << " -> " << r.end[i].fds << "\n";
  for (const auto& f : r.faults)
    s << "  " << f.name << ": " << f.framesAffected << " frames affected, " << f.offlineTiles << " tiles lost, "
      << f.reassignedItems << " items redone, " << f.failedFrames << " frames lost, recovery " << f.recoverySeconds
      << " s, frame time x" << f.frameSlowdown << (f.detail.empty() ? "" : "; " + f.detail) << "\n";
  return s.str();
}

}  // namespace tsr::cluster::test
