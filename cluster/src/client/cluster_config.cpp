#include "tsr/cluster/cluster_config.hpp"

#include <algorithm>
#include <fstream>
#include <initializer_list>
#include <sstream>

#include <nlohmann/json.hpp>

namespace tsr::cluster {

namespace {

using json = nlohmann::json;

struct Reader {
  std::string source;
  [[noreturn]] void fail(const std::string& why) const { throw ConfigError(source + ": " + why); }

  template <class T>
  T get(const json& j, const char* key, T fallback) const {
    if (!j.contains(key)) return fallback;
    try {
      return j.at(key).get<T>();
    } catch (const json::exception&) {
      fail(std::string("'") + key + "' has the wrong type");
    }
  }
  std::uint32_t positive(const json& j, const char* key, std::uint32_t fallback) const {
    std::int64_t v = get<std::int64_t>(j, key, fallback);
    if (v <= 0 || v > 65535) fail(std::string("'") + key + "' must be 1..65535");
    return static_cast<std::uint32_t>(v);
  }
  std::chrono::milliseconds millis(const json& j, const char* key, std::chrono::milliseconds fallback) const {
    std::int64_t v = get<std::int64_t>(j, key, fallback.count());
    if (v <= 0) fail(std::string("'") + key + "' must be positive");
    return std::chrono::milliseconds(v);
  }
  med::Parameters parameters(const json& j, med::Parameters base) const {
    if (!j.contains("parameters")) return base;
    const json& p = j.at("parameters");
    if (!p.is_object()) fail("'parameters' must be an object");
    for (auto it = p.begin(); it != p.end(); ++it) {
      const json& v = it.value();
      if (v.is_boolean())
        base.set(it.key(), v.get<bool>());
      else if (v.is_number_integer())
        base.set(it.key(), v.get<std::int64_t>());
      else if (v.is_number())
        base.set(it.key(), v.get<double>());
      else if (v.is_string())
        base.set(it.key(), v.get<std::string>());
      else
        fail("parameter '" + it.key() + "' must be a boolean, number or string");
    }
    return base;
  }
  // The keys an object of the config may hold: any other is most likely a
  // typo ('lateMS'), which would otherwise be ignored without a word.
  void only(const json& j, std::initializer_list<const char*> keys, const std::string& what) const {
    for (auto it = j.begin(); it != j.end(); ++it) {
      if (std::any_of(keys.begin(), keys.end(), [&](const char* k) { return it.key() == k; })) continue;
      std::string known;
      for (const char* k : keys) known += (known.empty() ? "" : ", ") + std::string(k);
      fail("unknown key '" + it.key() + "' in " + what + " (it takes " + known + ")");
    }
  }
  const json& object(const json& j, const char* key) const {
    static const json empty = json::object();
    if (!j.contains(key)) return empty;
    if (!j.at(key).is_object()) fail(std::string("'") + key + "' must be an object");
    return j.at(key);
  }
};

}  // namespace

void ClusterConfig::replaceAddresses(const std::vector<NodeAddress>& addresses) {
  if (nodes.empty() && !addresses.empty())
    throw ConfigError("config names no node to take the addresses' settings from");
  for (std::size_t i = 0; i < addresses.size(); ++i) {
    if (i >= nodes.size()) nodes.push_back(nodes.front());
    nodes[i].address = addresses[i];
  }
}

void ClusterConfig::validate() const {
  if (nodes.empty()) throw ConfigError("no nodes");
  for (const auto& n : nodes)
    if (n.backend.empty()) throw ConfigError("node " + n.address.text() + " has no back-end");
  if (mode == ClusterMode::Tiled && wall.screens.empty() && std::size_t{wall.columns} * wall.rows != nodes.size())
    throw ConfigError("a " + std::to_string(wall.columns) + "x" + std::to_string(wall.rows) + " wall needs " +
                      std::to_string(wall.columns * wall.rows) + " nodes, the config has " +
                      std::to_string(nodes.size()));
  if (mode == ClusterMode::Tiled && !wall.screens.empty() && wall.screens.size() != nodes.size())
    throw ConfigError("a wall of " + std::to_string(wall.screens.size()) +
                      " screens needs as many nodes, the config has " + std::to_string(nodes.size()));
  if (!wall.screens.empty()) {
    if (wall.frameWidth == 0 || wall.frameHeight == 0) throw ConfigError("wall 'frame' must be [width, height]");
    for (std::size_t i = 0; i < wall.screens.size(); ++i) {
      const ScreenConfig& s = wall.screens[i];
      std::string which = "screen " + std::to_string(i);
      if (s.eye.has_value() != wall.screens.front().eye.has_value())
        throw ConfigError(which + ": either every screen names an eye or none does");
      if (s.width == 0 || s.height == 0) throw ConfigError(which + " has no size");
      std::int64_t x0 = std::int64_t{s.x} + s.bezel, x1 = std::int64_t{s.x} + s.width - s.bezel;
      std::int64_t y0 = std::int64_t{s.y} + s.bezel, y1 = std::int64_t{s.y} + s.height - s.bezel;
      if (x1 <= std::max<std::int64_t>(x0, 0) || y1 <= std::max<std::int64_t>(y0, 0) || x0 >= wall.frameWidth ||
          y0 >= wall.frameHeight)
        throw ConfigError(which + " shows no pixel of the " + std::to_string(wall.frameWidth) + "x" +
                          std::to_string(wall.frameHeight) + " frame (rectangle, bezel)");
    }
  }
}

namespace {

// "mode": cooperative, tiled (or wall), stereo.
void readMode(const Reader& r, const json& j, ClusterConfig& c) {
  std::string mode = r.get<std::string>(j, "mode", "cooperative");
  if (mode == "cooperative")
    c.mode = ClusterMode::Cooperative;
  else if (mode == "tiled" || mode == "wall")
    c.mode = ClusterMode::Tiled;
  else if (mode == "stereo")
    c.mode = ClusterMode::Stereo;
  else
    r.fail("unknown mode '" + mode + "' (cooperative, tiled, stereo)");
}

// "compression" of the pixels nodes send: lz4, zstd, none.
void readCompression(const Reader& r, const json& j, ClusterConfig& c) {
  std::string compression = r.get<std::string>(j, "compression", "lz4");
  if (compression == "lz4")
    c.compression = Compression::Lz4;
  else if (compression == "zstd")
    c.compression = Compression::Zstd;
  else if (compression == "none")
    c.compression = Compression::None;
  else
    r.fail("unknown compression '" + compression + "' (lz4, zstd, none)");
}

// "nodes", each with the config's back-end and parameters unless it names its own.
void readNodes(const Reader& r, const json& j, ClusterConfig& c) {
  std::string backend = r.get<std::string>(j, "backend", "embree");
  med::Parameters defaults = r.parameters(j, {});
  if (!j.contains("nodes") || !j.at("nodes").is_array()) r.fail("'nodes' must be an array");
  for (const json& n : j.at("nodes")) {
    if (!n.is_object()) r.fail("each node must be an object");
    r.only(n, {"address", "backend", "parameters"}, "a node");
    NodeConfig node;
    try {
      node.address = parseNodeAddress(r.get<std::string>(n, "address", "127.0.0.1:0"));
    } catch (const std::invalid_argument& e) {
      r.fail(e.what());
    }
    node.backend = r.get<std::string>(n, "backend", backend);
    // The config's parameters are its back-end's: a node that names another
    // back-end has only its own.
    node.parameters = r.parameters(n, node.backend == backend ? defaults : med::Parameters{});
    c.nodes.push_back(std::move(node));
  }
}

// "cooperative": tiles and their balancing.
void readCooperative(const Reader& r, const json& j, ClusterConfig& c) {
  const json& coop = r.object(j, "cooperative");
  r.only(coop, {"tileSize", "tolerance", "maxMovesPerFrame"}, "'cooperative'");
  c.cooperative.tileSize = r.positive(coop, "tileSize", c.cooperative.tileSize);
  c.cooperative.tolerance = r.get<double>(coop, "tolerance", c.cooperative.tolerance);
  if (!(c.cooperative.tolerance >= 0)) r.fail("'tolerance' must not be negative");
  c.cooperative.maxMovesPerFrame = r.positive(coop, "maxMovesPerFrame", c.cooperative.maxMovesPerFrame);
}

// A screen's window: where it opens on the node's display, and how big.
WindowPlacement readWindow(const Reader& r, const json& wj) {
  r.only(wj, {"position", "size", "fullscreen"}, "a screen's 'window'");
  WindowPlacement w;
  auto pos = r.get<std::vector<std::int64_t>>(wj, "position", {0, 0});
  auto size = r.get<std::vector<std::int64_t>>(wj, "size", {0, 0});
  if (pos.size() != 2 || size.size() != 2)
    r.fail("a window's 'position' and 'size' must be [x, y] and [width, height]");
  for (std::int64_t v : pos)
    if (v < -(1 << 20) || v > 1 << 20) r.fail("a window's 'position' must lie within +-1048576");
  for (std::int64_t v : size)
    if (v < 0 || v > 16384) r.fail("a window's 'size' must be 0..16384 (0: the screen's pixels)");
  w.x = static_cast<std::int32_t>(pos[0]);
  w.y = static_cast<std::int32_t>(pos[1]);
  w.width = static_cast<std::uint32_t>(size[0]);
  w.height = static_cast<std::uint32_t>(size[1]);
  w.fullscreen = r.get<bool>(wj, "fullscreen", false);
  return w;
}

// One screen of a wall: its rectangle of the virtual frame, bezel, eye and window.
ScreenConfig readScreen(const Reader& r, const json& sj) {
  if (!sj.is_object()) r.fail("each screen must be an object");
  r.only(sj, {"rect", "bezel", "eye", "window"}, "a screen");
  ScreenConfig s;
  auto rect = r.get<std::vector<std::int64_t>>(sj, "rect", {});
  if (rect.size() != 4) r.fail("a screen's 'rect' must be [x, y, width, height]");
  for (std::int64_t v : rect)
    if (v < -(1 << 20) || v > 1 << 20) r.fail("a screen's 'rect' must lie within +-1048576");
  if (rect[2] <= 0 || rect[3] <= 0) r.fail("a screen's 'rect' must have a positive width and height");
  s.x = static_cast<std::int32_t>(rect[0]);
  s.y = static_cast<std::int32_t>(rect[1]);
  s.width = static_cast<std::uint32_t>(rect[2]);
  s.height = static_cast<std::uint32_t>(rect[3]);
  std::int64_t b = r.get<std::int64_t>(sj, "bezel", 0);
  if (b < -65535 || b > 65535) r.fail("a screen's 'bezel' must be -65535..65535");
  s.bezel = static_cast<std::int32_t>(b);
  if (sj.contains("eye")) {
    std::string eye = r.get<std::string>(sj, "eye", "");
    if (eye == "left")
      s.eye = med::Eye::Left;
    else if (eye == "right")
      s.eye = med::Eye::Right;
    else
      r.fail("unknown eye '" + eye + "' (left, right)");
  }
  if (sj.contains("window")) s.window = readWindow(r, r.object(sj, "window"));
  return s;
}

// "wall": a grid of columns and rows, or screens one by one in a virtual frame.
void readWall(const Reader& r, const json& j, ClusterConfig& c) {
  const json& wall = r.object(j, "wall");
  r.only(wall, {"columns", "rows", "bezel", "frame", "screens", "offlineColour"}, "'wall'");
  c.wall.columns = r.positive(wall, "columns", c.wall.columns);
  c.wall.rows = r.positive(wall, "rows", c.wall.rows);
  std::int64_t bezel = r.get<std::int64_t>(wall, "bezel", 0);
  if (bezel < 0 || bezel > 65535) r.fail("grid 'bezel' must be 0..65535 (overlap needs 'screens')");
  c.wall.bezel = static_cast<std::uint32_t>(bezel);
  if (wall.contains("screens")) {
    auto frame = r.get<std::vector<std::int64_t>>(wall, "frame", {});
    if (frame.size() != 2 || frame[0] <= 0 || frame[1] <= 0 || frame[0] > 1 << 20 || frame[1] > 1 << 20)
      r.fail("wall 'frame' must be [width, height] in pixels, each 1..1048576");
    c.wall.frameWidth = static_cast<std::uint32_t>(frame[0]);
    c.wall.frameHeight = static_cast<std::uint32_t>(frame[1]);
    if (!wall.at("screens").is_array() || wall.at("screens").size() > 4096)
      r.fail("'screens' must be an array (at most 4096)");
    for (const json& sj : wall.at("screens")) c.wall.screens.push_back(readScreen(r, sj));
  }
  if (wall.contains("offlineColour")) {
    auto rgb = r.get<std::vector<float>>(wall, "offlineColour", {});
    if (rgb.size() != 3) r.fail("'offlineColour' must be [r, g, b]");
    c.wall.offlineColour = glm::vec4(rgb[0], rgb[1], rgb[2], 1.0f);
  }
}

// "stereo": how the eyes are composed, and their separation and zero parallax.
void readStereo(const Reader& r, const json& j, ClusterConfig& c) {
  const json& stereo = r.object(j, "stereo");
  r.only(stereo, {"compose", "eyeSeparation", "zeroParallax"}, "'stereo'");
  std::string compose = r.get<std::string>(stereo, "compose", "anaglyph");
  if (compose == "anaglyph")
    c.stereo.compose = StereoCompose::Anaglyph;
  else if (compose == "side-by-side")
    c.stereo.compose = StereoCompose::SideBySide;
  else
    r.fail("unknown stereo composition '" + compose + "' (anaglyph, side-by-side)");
  if (stereo.contains("eyeSeparation")) c.stereo.eyeSeparation = r.get<float>(stereo, "eyeSeparation", 0);
  if (stereo.contains("zeroParallax")) c.stereo.zeroParallax = r.get<float>(stereo, "zeroParallax", 0);
  if (c.stereo.zeroParallax && !(*c.stereo.zeroParallax > 0)) r.fail("'zeroParallax' must be positive");
}

// "snapshotPartKiB": the part size of a scene larger than it.
void readSnapshotParts(const Reader& r, const json& j, ClusterConfig& c) {
  const std::int64_t kib = r.get<std::int64_t>(j, "snapshotPartKiB", 0);
  if (kib < 0 || kib > (std::int64_t{1} << 20)) r.fail("'snapshotPartKiB' must be 0..1048576 (0: 1 GiB)");
  c.snapshotPartBytes = static_cast<std::size_t>(kib) * 1024;
}

// "timeouts", in milliseconds.
void readTimeouts(const Reader& r, const json& j, ClusterConfig& c) {
  const json& t = r.object(j, "timeouts");
  r.only(t, {"connectMs", "frameMs", "heartbeatMs", "deadAfterMs", "retryMs", "lateMs"}, "'timeouts'");
  c.timeouts.connect = r.millis(t, "connectMs", c.timeouts.connect);
  c.timeouts.frame = r.millis(t, "frameMs", c.timeouts.frame);
  c.timeouts.heartbeat = r.millis(t, "heartbeatMs", c.timeouts.heartbeat);
  c.timeouts.deadAfter = r.millis(t, "deadAfterMs", c.timeouts.deadAfter);
  c.timeouts.retry = r.millis(t, "retryMs", c.timeouts.retry);
  c.timeouts.late = r.millis(t, "lateMs", c.timeouts.late);
}

}  // namespace

// The config's sections in order, each read and checked by its own step;
// the first problem fails the whole with the source named.
ClusterConfig parseClusterConfig(const std::string& text, const std::string& source) {
  Reader r{source};
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    r.fail(std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object()) r.fail("the top level must be an object");
  r.only(j,
         {"mode", "compression", "backend", "parameters", "nodes", "cooperative", "wall", "stereo", "timeouts",
          "snapshotPartKiB"},
         "the config");
  ClusterConfig c;
  readMode(r, j, c);
  readCompression(r, j, c);
  readNodes(r, j, c);
  readCooperative(r, j, c);
  readWall(r, j, c);
  readStereo(r, j, c);
  readTimeouts(r, j, c);
  readSnapshotParts(r, j, c);
  try {
    c.validate();
  } catch (const ConfigError& e) {
    r.fail(e.what());
  }
  return c;
}

ClusterConfig loadClusterConfig(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError("cannot read cluster config '" + path + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  return parseClusterConfig(ss.str(), path);
}

}  // namespace tsr::cluster
