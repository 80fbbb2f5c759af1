#include "sequence_render.hpp"

#include <chrono>
#include <functional>
#include <iostream>
#include <stdexcept>

#include "backends.hpp"
#include "scene_session.hpp"
#include "tsr/cluster/auth.hpp"
#include "tsr/cluster/cluster_window.hpp"
#include "tsr/med/image_file.hpp"
#include "tsr/med/viewport_registry.hpp"

namespace tsr::app {

namespace {

using FrameRenderer = std::function<med::FrameBuffer(SceneSession&, const sg::ChangeListPtr&, const med::View&)>;

FrameRenderer localRenderer(const RenderOptions& options, const SceneSession& session) {
  auto registry = std::make_shared<med::ViewportRegistry>();
  registerBackends(*registry);
  auto contexts = std::make_shared<med::ContextPool>();
  med::ViewportSettings settings{options.backend, session.imported.root, session.imported.background, options.parameters, true};
  std::shared_ptr<med::Viewport> viewport = registry->create(settings, *contexts);
  med::RenderControl control;
  control.outputs = options.aovs;
  return [registry, contexts, viewport, control](SceneSession& s, const sg::ChangeListPtr&, const med::View& view) {
    med::FrameBuffer image;
    viewport->render(s.replica, view, image, control);
    return image;
  };
}

FrameRenderer clusterRenderer(const RenderOptions& options, const SequenceOptions& sequence, const SceneSession& session) {
  cluster::ClusterConfig config = cluster::loadClusterConfig(sequence.cluster);
  if (!sequence.nodes.empty()) config.replaceAddresses(cluster::parseNodeList(sequence.nodes));
  // What the command line names beats the config; the config beats the
  // command line's defaults.
  for (auto& node : config.nodes)
    for (const auto& [name, value] : options.parameters.all())
      if (options.explicitParameters.count(name) || !node.parameters.has(name)) node.parameters.set(name, value);
  config.validate();
  cluster::ClientOptions client;
  if (!sequence.tokenFile.empty()) client.token = cluster::readTokenFile(sequence.tokenFile);
  client.outputs = options.aovs;
  // Whole-frame image steps of the nodes' back-end (pixel filtering) run
  // here on the assembled frame, so tiles show no seams.
  auto registry = std::make_shared<med::ViewportRegistry>();
  registerBackends(*registry);
  client.registry = registry.get();
  auto window = std::shared_ptr<cluster::ClusterWindow>(new cluster::ClusterWindow(config, client),
                                                        [registry](cluster::ClusterWindow* w) { delete w; });
  window->setContent(session.imported.root, session.imported.background);
  std::size_t online = window->connect(config.timeouts.connect);
  if (online == 0 && config.mode != cluster::ClusterMode::Tiled)
    throw std::runtime_error("no cluster node could be reached: " + window->status().front().lastError);
  if (!options.quiet) std::cout << online << " of " << config.nodes.size() << " nodes online\n";
  return [window](SceneSession& s, const sg::ChangeListPtr& delta, const med::View& view) {
    const auto* camera = s.source.find<sg::Camera>(s.camera);
    window->setEyes(camera->eyeSeparation(), camera->zeroParallaxDistance());
    window->publish(s.source, delta);
    return window->render(view).image;
  };
}

}  // namespace

int renderSequence(const RenderOptions& options, const SequenceOptions& sequence) {
  if (sequence.frames > 1 && options.output.find("####") == std::string::npos)
    throw std::invalid_argument("--frames " + std::to_string(sequence.frames) + " needs #### in --output for the frame number");
  SceneSession session;
  session.load(options.scene, options.import);
  FrameRenderer render = sequence.cluster.empty() ? localRenderer(options, session) : clusterRenderer(options, sequence, session);
  for (int frame = 0; frame < sequence.frames; ++frame) {
    // Frame 0 is the scene as loaded; later ones pose the animation at frame / fps.
    if (sequence.framesGiven)
      for (const auto& animation : session.imported.animations)
        animation.apply(session.source, static_cast<float>(frame / sequence.fps));
    auto delta = session.publish();
    const auto* camera = session.replica.scene().find<sg::Camera>(session.camera);
    auto view = med::View::fromCamera(*camera, options.width, options.height);
    auto started = std::chrono::steady_clock::now();
    med::FrameBuffer image = render(session, delta, view);
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::string path = framePath(options.output, frame);
    med::writeImage(path, image);
    for (const auto& aov : options.aovs) med::writeImage(aovPath(path, aov), image, aov);
    if (!options.quiet)
      std::cout << "wrote " << path << " (" << image.width << "x" << image.height << ", " << seconds << " s)\n";
  }
  return 0;
}

}  // namespace tsr::app
