#pragma once
// One client on a node: the handshake, then one handler per message.
// Handlers that touch the replica or render hand their work to the render
// worker; results come back to the io thread as frames.
#include <atomic>
#include <map>
#include <memory>
#include <tuple>

#include "node/render_worker.hpp"
#include "protocol/connection.hpp"
#include "tsr/cluster/node_server.hpp"
#include "tsr/med/context_pool.hpp"
#include "tsr/med/viewport_registry.hpp"
#include "tsr/sg/replica.hpp"

namespace tsr::cluster {

struct RenderRequest;

struct NodeContext {
  NodeOptions options;
  const med::ViewportRegistry& registry;
  RenderWorker& worker;
};

class NodeSession : public std::enable_shared_from_this<NodeSession> {
 public:
  NodeSession(tcp::socket socket, NodeContext& context);
  ~NodeSession();
  void start();

 private:
  // What the worker thread owns. Contexts before viewports: viewports
  // release their contexts when they go.
  struct State {
    std::unique_ptr<sg::Replica> replica = std::make_unique<sg::Replica>();
    med::ContextPool contexts;
    std::map<std::uint32_t, med::ViewportSettings> settings;
    using Key = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>;
    std::map<Key, std::unique_ptr<med::Viewport>> viewports;  // one per (viewport, rect): tiles keep their samples
    // Viewports that look ahead (photons, object-space PCA) see every frame
    // of an animation before they show it: one per viewport id, for all its
    // rectangles, fed by Prepare from a second replica, the scene ahead.
    std::unique_ptr<sg::Replica> ahead = std::make_unique<sg::Replica>();
    std::map<std::uint32_t, std::unique_ptr<med::Viewport>> sequences;
    std::uint64_t lastFrame = ~std::uint64_t{0};
    // The last frame's tiles, held until its Swap: what a wall node shows.
    std::vector<PresentedTile> backBuffer;
    std::optional<WindowPlacement> window;  // where the client's config shows our screen
    std::atomic<bool> cancelled{false};
  };

  asio::awaitable<void> run();
  asio::awaitable<bool> handshake();
  void dispatch(Message& m);

  // The handler of message M (one a client sends after the handshake),
  // specialised in node_session.cpp; dispatch() picks it by the message list.
  template <class M>
  void on(Message& m);
  void onReplicaBytes(Message& m, bool snapshot);

  // Worker side.
  static void render(State& state, const NodeContext& ctx, const RenderRequest& request,
                     const std::shared_ptr<Connection>& conn);
  void failFromWorker(ErrorReport::Kind kind, const std::string& reason);

  NodeContext& ctx_;
  std::shared_ptr<Connection> conn_;
  std::shared_ptr<State> state_ = std::make_shared<State>();
  std::string peer_;
};

}  // namespace tsr::cluster
