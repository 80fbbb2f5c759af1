#pragma once
// A cluster setup as described by a JSON file in configs/: the nodes, the
// mode, and per node the back-end and its parameters (falling back to the
// file's defaults). Example:
//   { "mode": "cooperative", "backend": "embree",
//     "parameters": { "spp": 4, "seed": 1 },
//     "nodes": [ { "address": "127.0.0.1:7201" },
//                { "address": "127.0.0.1:7202", "parameters": { "threads": 1 } } ],
//     "cooperative": { "tileSize": 32 } }
#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "tsr/cluster/messages.hpp"
#include "tsr/cluster/node_address.hpp"
#include "tsr/med/parameters.hpp"
#include "tsr/med/view.hpp"

namespace tsr::cluster {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ClusterMode { Cooperative, Tiled, Stereo };
enum class StereoCompose { Anaglyph, SideBySide };

struct NodeConfig {
  NodeAddress address;
  std::string backend;
  med::Parameters parameters;
};

struct CooperativeConfig {
  std::uint32_t tileSize = 32;
  double tolerance = 0.05;             // rebalance only when max/mean load exceeds 1 + tolerance
  std::uint32_t maxMovesPerFrame = 4;  // a moved tile loses its samples: move little at a time
};

// One screen of a wall that is not a grid (Tide and Equalizer describe
// walls so): its rectangle in the virtual frame, in the frame's pixels.
struct ScreenConfig {
  std::int32_t x = 0, y = 0;
  std::uint32_t width = 0, height = 0;
  // Pixels hidden behind the frame on each edge (mullion compensation);
  // negative: the screen shows that much beyond its rectangle, as
  // overlapping projectors do.
  std::int32_t bezel = 0;
  std::optional<med::Eye> eye;  // a stereo wall: which eye this screen shows
  std::optional<WindowPlacement> window;
};

struct WallConfig {
  // A grid: columns x rows screens with `bezel` hidden pixels between neighbours.
  std::uint32_t columns = 2, rows = 2;
  std::uint32_t bezel = 0;
  // Or screens one by one (non-empty wins over the grid), in a virtual
  // frame of frameWidth x frameHeight pixels scaled to the rendered size.
  std::uint32_t frameWidth = 0, frameHeight = 0;
  std::vector<ScreenConfig> screens;
  glm::vec4 offlineColour{0.25f, 0.0f, 0.25f, 1.0f};  // fill of a tile whose node is gone

  bool stereo() const { return !screens.empty() && screens.front().eye.has_value(); }
};

struct StereoConfig {
  StereoCompose compose = StereoCompose::Anaglyph;
  // Unset: the application's (the scene camera's) values, via setEyes().
  std::optional<float> eyeSeparation;
  std::optional<float> zeroParallax;
};

struct Timeouts {
  std::chrono::milliseconds connect{3000};
  std::chrono::milliseconds frame{120000};  // a node that misses this is dropped for the frame
  std::chrono::milliseconds heartbeat{500};
  std::chrono::milliseconds deadAfter{4000};  // no message for this long: the node is gone
  std::chrono::milliseconds retry{1000};      // between reconnection attempts
  // A node this long in one phase of a frame is reported late: ten times
  // this in its first frame after joining (it builds its scene), later at
  // least twice its longest wait for one tile in its previous frame.
  std::chrono::milliseconds late{1000};
};

struct ClusterConfig {
  ClusterMode mode = ClusterMode::Cooperative;
  std::vector<NodeConfig> nodes;
  Compression compression = Compression::Lz4;
  CooperativeConfig cooperative;
  WallConfig wall;
  StereoConfig stereo;
  Timeouts timeouts;
  // "snapshotPartKiB": the largest change list one Snapshot or Prepare
  // message carries; a larger scene goes to a node in parts
  // (sg::splitSnapshot). 0: the messages' limit, 1 GiB.
  std::size_t snapshotPartBytes = 0;

  // Replaces the node addresses in order (tessera-render --nodes); more
  // addresses than nodes add nodes with the defaults of the first.
  void replaceAddresses(const std::vector<NodeAddress>& addresses);
  // Throws ConfigError when the setup cannot work (e.g. a wall whose tile
  // count differs from the node count).
  void validate() const;
};

// Throws ConfigError naming the file and the offending key.
ClusterConfig parseClusterConfig(const std::string& json, const std::string& source = "config");
ClusterConfig loadClusterConfig(const std::string& path);

}  // namespace tsr::cluster
