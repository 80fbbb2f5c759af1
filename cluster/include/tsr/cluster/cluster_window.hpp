#pragma once
// The application's window onto a cluster (Schwenk 5.3.4): it mirrors the
// scene on every node with change lists and renders a view there as the
// config's mode says — tiled wall, cooperative tiles, or a stereo pair —
// assembling the result here. A node that dies or stops answering never
// blocks a frame beyond the timeouts of the config; it is retried and,
// when back, receives a snapshot and takes part again.
//
// Per frame: scene.commit() -> publish(scene, list) -> render(view).
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "tsr/cluster/cluster_config.hpp"
#include "tsr/cluster/messages.hpp"
#include "tsr/cluster/workload.hpp"
#include "tsr/med/frame_buffer.hpp"
#include "tsr/med/view.hpp"
#include "tsr/med/viewport_registry.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::cluster {

class ClusterError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ClientOptions {
  std::string token;  // empty only for nodes started without a token
  std::string name = "tessera-client";
  // Named outputs (AOVs) to assemble besides colour and depth. The
  // workload image (kWorkloadOutput) is drawn here from the frame's tiles,
  // in cooperative and mono tiled modes; the nodes fill the others.
  std::vector<std::string> outputs = {};
  // Where the nodes' back-end has whole-frame image steps (pixel filtering),
  // a viewport of it made from this registry resolves the assembled frame
  // here, so tiles show no seams. Null: every node resolves its own tiles.
  const med::ViewportRegistry* registry = nullptr;
};

enum class NodeState { Offline, Connecting, Joined, Synced };

// What the client waits for from a node: the connection, its replica
// catching up (a snapshot or change lists), its tiles, or its FrameDone
// before the frame's barrier releases. Idle: nothing.
enum class NodePhase { Idle, Connect, Snapshot, Render, Barrier };
const char* name(NodePhase phase);

struct NodeStatus {
  NodeAddress address;
  std::string name;  // as the node calls itself
  NodeState state = NodeState::Offline;
  std::uint64_t appliedVersion = 0;
  std::uint64_t bytesSent = 0;      // messages sent to this node, heartbeats aside
  std::uint64_t bytesReceived = 0;  // messages received from it
  std::string lastError;
  NodePhase phase = NodePhase::Idle;
  std::chrono::steady_clock::time_point phaseSince{};
  // The last ErrorReport the node sent since it joined: decide by its kind,
  // not by the text of lastError (which a lost connection overwrites).
  std::optional<ErrorReport> lastReport = {};
};

struct ClusterFrame {
  std::uint64_t frame = 0;
  med::FrameBuffer image;           // stitched wall, composited tiles, or the composed stereo pair
  med::FrameBuffer left, right;     // stereo only
  std::vector<double> busySeconds;  // per node (config order): its whole requests; 0 where it did nothing
  std::vector<double> tileSeconds;  // per node: the part spent rendering its tiles
  // Every rectangle of the frame as placed: by which node (or given up), at
  // what cost. The cooperative tiles cover the frame once; a wall's screens
  // as its layout says (bezels leave pixels to none); a stereo pair's, each
  // eye's whole view. summarizeWorkload() adds them up per node.
  std::vector<TileWork> tiles;
  std::vector<std::size_t> participants;  // the nodes online when the frame was planned
  std::size_t offlineTiles = 0;           // wall tiles shown as offline fill
  std::size_t reassignedItems = 0;        // work taken over from nodes lost during the frame
  // Nodes that were late (past timeouts.late in one phase) during the frame:
  // one line each, "ADDRESS (NAME): PHASE since HH:MM:SS.mmm (S s)".
  std::vector<std::string> lateNodes;
  // The client's share: decoding and placing tiles, and the spread of the
  // nodes' FrameDone (the barrier's wait for the slowest).
  double assembleSeconds = 0;
  double barrierSeconds = 0;
  // The wall's pixels stayed on the nodes (keepPixelsOnNodes): `image`
  // holds only the offline fill.
  bool pixelsKept = false;
};

struct ReplicaHash {
  std::size_t node = 0;
  std::uint64_t version = 0;
  std::uint64_t hash = 0;
};

class ClusterWindow {
 public:
  // Throws ClusterError when the options ask for the workload image of a
  // stereo setup (its two eyes share no frame to colour).
  ClusterWindow(ClusterConfig config, ClientOptions options = {});
  ~ClusterWindow();
  ClusterWindow(const ClusterWindow&) = delete;
  ClusterWindow& operator=(const ClusterWindow&) = delete;

  // Connects to every node, waiting at most `timeout`; returns how many
  // joined. Nodes that did not are retried at every publish().
  std::size_t connect(std::chrono::milliseconds timeout);
  // A node joining mid-session; it gets a snapshot at the next publish().
  std::size_t addNode(NodeConfig node);

  // What the viewports show: a root node (none: every root) and a
  // Background container (none: black), as in med::ViewportSettings.
  void setContent(sg::ContainerId root, sg::ContainerId background);

  // Sends `delta` (just committed, may be null) to the nodes that follow the
  // scene and a snapshot to those that joined. The scene must have no
  // pending edits.
  void publish(const sg::Scene& scene, const sg::ChangeListPtr& delta);
  // True once every synchronised node applied `version` (false on timeout).
  bool waitApplied(std::uint64_t version, std::chrono::milliseconds timeout);
  // The version and content hash of every synchronised node's replica.
  std::vector<ReplicaHash> replicaHashes(std::chrono::milliseconds timeout);

  // Animations for viewports that look ahead (med::Viewport::lookahead, the
  // path tracer's photons): sends every synchronised node frame `frame`
  // posed in `ahead`, a second copy of the scene, `delta` (may be null) the
  // list that brought it there from the frame before; a node that missed it
  // gets a snapshot. Frames go in order, each before the frame shown
  // lookahead() frames later is rendered. A node that joins during the
  // animation cannot show its frames (it saw none before).
  void prepare(const sg::Scene& ahead, const sg::ChangeListPtr& delta, std::int64_t frame);

  // Renders `view` (the full image) on the nodes as the mode says;
  // `sequenceFrame` is the animation frame shown, for viewports that look
  // ahead (-1: none). Throws ClusterError when no node is left to render
  // (wall: never; its tiles show the offline fill).
  ClusterFrame render(const med::View& view, std::int64_t sequenceFrame = -1);
  // Called on this thread as render()'s tiles arrive, with the share of the
  // frame's tiles done (0..1): progress to show while the nodes work.
  void setProgress(std::function<void(double)> progress);
  // Wall (tiled) mode: true lets the nodes keep their pixels, present them
  // and send none back, so the client's traffic no longer grows with the
  // wall's pixel count. For a client that shows no picture itself; the
  // frame then comes back without one (ClusterFrame::pixelsKept). Other
  // modes ignore it. Default false.
  void keepPixelsOnNodes(bool keep);
  // Stereo: eye separation and zero-parallax distance (the scene camera's);
  // values the config gives take precedence.
  void setEyes(float separation, float zeroParallax);

  std::vector<NodeStatus> status() const;
  std::size_t onlineNodes() const;
  const ClusterConfig& config() const;
  // Imbalance (max / mean) of the cooperative balancer's load estimate.
  double estimatedImbalance() const;
  // The last frame's tiles added up per node, with its measured balance
  // (summarizeWorkload); empty before the first frame.
  const FrameWorkload& lastWorkload() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tsr::cluster
