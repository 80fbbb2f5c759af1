#include "tsr/cluster/cluster_config.hpp"

#include <fstream>
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
      if (v.is_boolean()) base.set(it.key(), v.get<bool>());
      else if (v.is_number_integer()) base.set(it.key(), v.get<std::int64_t>());
      else if (v.is_number()) base.set(it.key(), v.get<double>());
      else if (v.is_string()) base.set(it.key(), v.get<std::string>());
      else fail("parameter '" + it.key() + "' must be a boolean, number or string");
    }
    return base;
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
  if (nodes.empty() && !addresses.empty()) throw ConfigError("config names no node to take the addresses' settings from");
  for (std::size_t i = 0; i < addresses.size(); ++i) {
    if (i >= nodes.size()) nodes.push_back(nodes.front());
    nodes[i].address = addresses[i];
  }
}

void ClusterConfig::validate() const {
  if (nodes.empty()) throw ConfigError("no nodes");
  for (const auto& n : nodes)
    if (n.backend.empty()) throw ConfigError("node " + n.address.text() + " has no back-end");
  if (mode == ClusterMode::Tiled && std::size_t{wall.columns} * wall.rows != nodes.size())
    throw ConfigError("a " + std::to_string(wall.columns) + "x" + std::to_string(wall.rows) + " wall needs " +
                      std::to_string(wall.columns * wall.rows) + " nodes, the config has " + std::to_string(nodes.size()));
}

ClusterConfig parseClusterConfig(const std::string& text, const std::string& source) {
  Reader r{source};
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    r.fail(std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object()) r.fail("the top level must be an object");
  ClusterConfig c;
  std::string mode = r.get<std::string>(j, "mode", "cooperative");
  if (mode == "cooperative") c.mode = ClusterMode::Cooperative;
  else if (mode == "tiled" || mode == "wall") c.mode = ClusterMode::Tiled;
  else if (mode == "stereo") c.mode = ClusterMode::Stereo;
  else r.fail("unknown mode '" + mode + "' (cooperative, tiled, stereo)");

  std::string compression = r.get<std::string>(j, "compression", "lz4");
  if (compression == "lz4") c.compression = Compression::Lz4;
  else if (compression == "zstd") c.compression = Compression::Zstd;
  else if (compression == "none") c.compression = Compression::None;
  else r.fail("unknown compression '" + compression + "' (lz4, zstd, none)");

  std::string backend = r.get<std::string>(j, "backend", "embree");
  med::Parameters defaults = r.parameters(j, {});
  if (!j.contains("nodes") || !j.at("nodes").is_array()) r.fail("'nodes' must be an array");
  for (const json& n : j.at("nodes")) {
    if (!n.is_object()) r.fail("each node must be an object");
    NodeConfig node;
    try {
      node.address = parseNodeAddress(r.get<std::string>(n, "address", "127.0.0.1:0"));
    } catch (const std::invalid_argument& e) {
      r.fail(e.what());
    }
    node.backend = r.get<std::string>(n, "backend", backend);
    node.parameters = r.parameters(n, defaults);
    c.nodes.push_back(std::move(node));
  }

  const json& coop = r.object(j, "cooperative");
  c.cooperative.tileSize = r.positive(coop, "tileSize", c.cooperative.tileSize);
  c.cooperative.tolerance = r.get<double>(coop, "tolerance", c.cooperative.tolerance);
  if (!(c.cooperative.tolerance >= 0)) r.fail("'tolerance' must not be negative");
  c.cooperative.maxMovesPerFrame = r.positive(coop, "maxMovesPerFrame", c.cooperative.maxMovesPerFrame);

  const json& wall = r.object(j, "wall");
  c.wall.columns = r.positive(wall, "columns", c.wall.columns);
  c.wall.rows = r.positive(wall, "rows", c.wall.rows);
  c.wall.bezel = static_cast<std::uint32_t>(r.get<std::int64_t>(wall, "bezel", 0));
  if (wall.contains("offlineColour")) {
    auto rgb = r.get<std::vector<float>>(wall, "offlineColour", {});
    if (rgb.size() != 3) r.fail("'offlineColour' must be [r, g, b]");
    c.wall.offlineColour = glm::vec4(rgb[0], rgb[1], rgb[2], 1.0f);
  }

  const json& stereo = r.object(j, "stereo");
  std::string compose = r.get<std::string>(stereo, "compose", "anaglyph");
  if (compose == "anaglyph") c.stereo.compose = StereoCompose::Anaglyph;
  else if (compose == "side-by-side") c.stereo.compose = StereoCompose::SideBySide;
  else r.fail("unknown stereo composition '" + compose + "' (anaglyph, side-by-side)");
  if (stereo.contains("eyeSeparation")) c.stereo.eyeSeparation = r.get<float>(stereo, "eyeSeparation", 0);
  if (stereo.contains("zeroParallax")) c.stereo.zeroParallax = r.get<float>(stereo, "zeroParallax", 0);
  if (c.stereo.zeroParallax && !(*c.stereo.zeroParallax > 0)) r.fail("'zeroParallax' must be positive");

  const json& t = r.object(j, "timeouts");
  c.timeouts.connect = r.millis(t, "connectMs", c.timeouts.connect);
  c.timeouts.frame = r.millis(t, "frameMs", c.timeouts.frame);
  c.timeouts.heartbeat = r.millis(t, "heartbeatMs", c.timeouts.heartbeat);
  c.timeouts.deadAfter = r.millis(t, "deadAfterMs", c.timeouts.deadAfter);
  c.timeouts.retry = r.millis(t, "retryMs", c.timeouts.retry);
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
