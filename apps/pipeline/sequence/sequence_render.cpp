#include "sequence/sequence_render.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <functional>
#include <iostream>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "backends.hpp"
#include "cluster/cluster_connection.hpp"
#include "cluster/cluster_layer.hpp"
#include "cluster/cluster_stats.hpp"
#include "option_values.hpp"
#include "outputs/stats_json.hpp"
#include "progress_bar.hpp"
#include "scene/scene_session.hpp"
#include "sequence/high_sample_frames.hpp"
#include "sequence/temporal_pca_sequence.hpp"
#include "tsr/cluster/cluster_window.hpp"
#include "tsr/med/image_file.hpp"
#include "tsr/med/viewport_registry.hpp"

namespace tsr::app {

namespace {

using FrameRenderer =
    std::function<med::FrameBuffer(SceneSession&, const sg::ChangeListPtr&, const med::View&, int frame)>;

// How a sequence is rendered: frame by frame, or by a window whose layers
// must see `lookahead` frames of the animation before they show one.
struct SequenceRenderer {
  FrameRenderer render;
  std::uint32_t lookahead = 0;
  std::function<void(const sg::Replica& ahead, int frame)> prepare;
};

// The outputs every frame needs: the --aov ones, and with --temporal the
// split the PCA step works on.
std::vector<std::string> frameOutputs(const RenderJob& options) {
  std::vector<std::string> outputs = options.aovs;
  if (options.temporal.imagePca())
    for (const char* name : {"direct", "indirect"})
      if (std::find(outputs.begin(), outputs.end(), name) == outputs.end()) outputs.emplace_back(name);
  return outputs;
}

// The window a local sequence renders through, with what it refers to
// (declared first, so destroyed last).
struct LocalWindow {
  med::ViewportRegistry registry;
  med::ContextPool contexts;
  med::Window window;
};

// Every frame through a window of the --layers (none: --backend alone), a
// layer of them on the --cluster nodes when one is given.
// With --temporal, each frame gets its own seed (frame-by-frame renders
// share one, so a static pixel's noise would repeat in every frame and look
// like signal to the temporal step), and direct light, when --direct-spp
// asks for more, continues the same progressive accumulation past --spp:
// the indirect output is read at --spp, the direct one at --direct-spp.
// With --temporal photons, the path tracer's photon layer sees each frame
// its lookahead ahead of the one shown. `stats` adds up every render.
SequenceRenderer localRenderer(const RenderJob& options, const std::vector<LayerSpec>& layers,
                               const SceneSession& session, med::RenderStats& stats) {
  auto local = std::make_shared<LocalWindow>();
  registerBackends(local->registry);
  med::ViewportSettings settings{options.backend, session.imported.root, session.imported.background,
                                 options.parameters, true};
  RemoteLayers remote;
  if (!options.sequence.cluster.empty())
    remote = clusterLayer(options, layers, local->registry, *session.source.find<sg::Camera>(session.camera));
  local->window = makeLayeredWindow(layers, session.source, settings, local->registry, local->contexts, remote);
  checkOutputsOffered(options.aovs, local->window);
  med::RenderControl shown;
  shown.outputs = frameOutputs(options);
  const bool temporal = options.temporal.imagePca();
  const med::ParameterTable& table = local->registry.capabilities(options.backend).parameters;
  const std::int64_t seed = table.declares("seed") ? table.integer(options.parameters, "seed") : 0;
  const std::int64_t spp = table.declares("spp") ? table.integer(options.parameters, "spp") : 1;
  const std::int64_t directSpp = std::max<std::int64_t>(spp, options.temporal.directSpp);
  SequenceRenderer sequence;
  sequence.lookahead = local->window.lookahead();
  sequence.prepare = [local](const sg::Replica& ahead, int frame) { local->window.prepare(ahead, frame); };
  sequence.render = [=, &stats](SceneSession& s, const sg::ChangeListPtr&, const med::View& view, int frame) {
    med::Window& window = local->window;
    med::RenderControl control = shown;
    control.frame = frame;
    auto set = [&](const std::string& name, std::int64_t value) {
      for (const auto& layer : window.layers()) layer->setParameter(name, value);
    };
    if (temporal) {
      set("seed", seed + frame);
      set("spp", spp);
    }
    med::FrameBuffer image, more;
    addStats(stats, renderLayered(window, s.replica, view, image, control));
    if (temporal && directSpp > spp) {
      set("spp", directSpp);
      med::RenderControl direct = control;
      direct.outputs = std::vector<std::string>{"direct"};
      addStats(stats, renderLayered(window, s.replica, view, more, direct));
      image.outputs["direct"] = std::move(more.outputs["direct"]);
    }
    return image;
  };
  return sequence;
}

// Whether an animation moves the camera (its node or one above it).
bool cameraMoves(const SceneSession& session) {
  std::unordered_set<sg::ContainerId> animated;
  for (const auto& animation : session.imported.animations)
    for (sg::ContainerId target : animation.targets()) animated.insert(target);
  if (animated.empty()) return false;
  const sg::Scene& scene = session.source;
  std::unordered_map<sg::ContainerId, std::vector<sg::ContainerId>> parents;
  auto note = [&](sg::ContainerId parent, const std::vector<sg::ContainerId>& children) {
    for (sg::ContainerId child : children) parents[child].push_back(parent);
  };
  for (sg::ContainerId id : scene.ids()) {
    if (const auto* t = scene.find<sg::Transform>(id)) note(id, t->children());
    if (const auto* g = scene.find<sg::Group>(id)) note(id, g->children());
  }
  std::vector<sg::ContainerId> above{session.camera};
  std::unordered_set<sg::ContainerId> seen;
  while (!above.empty()) {
    const sg::ContainerId id = above.back();
    above.pop_back();
    if (animated.count(id)) return true;
    if (!seen.insert(id).second) continue;
    for (sg::ContainerId parent : parents[id]) above.push_back(parent);
  }
  return false;
}

// The back-ends that declare `parameter`: "temporal" for a temporal photon
// pass, "history" for reprojected samples.
std::vector<std::string> backendsDeclaring(const std::string& parameter) {
  const med::ViewportRegistry& registry = backendRegistry();
  std::vector<std::string> names;
  for (const auto& b : registry.backends())
    if (registry.capabilities(b).parameters.declares(parameter)) names.push_back(b);
  return names;
}

std::string backendChoice(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& b : names) text += (text.empty() ? "--backend " : " or --backend ") + b;
  return text;
}

// `log` records every frame's tiles and their cost (--stats-json).
// `progress` hears the share of each frame's tiles done as they arrive.
FrameRenderer clusterRenderer(const RenderJob& options, const SceneSession& session, ClusterStatsLog& log,
                              std::function<void(double)> progress) {
  auto registry = std::make_shared<med::ViewportRegistry>();
  registerBackends(*registry);
  std::shared_ptr<cluster::ClusterWindow> window{
      connectCluster(clusterConfig(options), options, frameOutputs(options), *registry).release(),
      [registry](cluster::ClusterWindow* w) { delete w; }};
  window->setContent(session.imported.root, session.imported.background);
  window->setProgress(std::move(progress));
  return [window, &log](SceneSession& s, const sg::ChangeListPtr& delta, const med::View& view, int frame) {
    const auto started = std::chrono::steady_clock::now();
    const auto* camera = s.source.find<sg::Camera>(s.camera);
    window->setEyes(camera->eyeSeparation(), camera->zeroParallaxDistance());
    window->publish(s.source, delta);
    cluster::ClusterFrame rendered = window->render(view, frame);  // the frame, for seedPerFrame
    log.record(frame, std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), rendered,
               *window);
    return std::move(rendered.image);
  };
}

// The temporal method as messages name it: "pca (image space)", "photons".
std::string temporalName(const TemporalOptions& temporal) {
  return temporal.method + (temporal.method == "pca" ? " (" + temporal.space + " space)" : "");
}

// The job as the sequence runs it: --temporal-space auto settles on the
// scene's camera; what depends on it is checked here, the rest with the
// command line.
RenderJob sequenceJob(const RenderJob& given, const SceneSession& session, const std::vector<LayerSpec>& layers) {
  RenderJob options = given;
  const bool moves = cameraMoves(session);
  options.temporal.resolveSpace(moves);
  if (given.temporal.method == "pca" && given.temporal.space == "auto" && !given.quiet)
    std::cout << "--temporal pca in " << options.temporal.space << " space: the camera "
              << (moves ? "moves" : "stays still") << " (--temporal-space chooses)\n";
  checkTemporalOptions(options.temporal, static_cast<int>(samplesPerPixel(options)));
  options.temporal.applyTo(options.parameters);
  const std::string method = temporalName(options.temporal);
  if (options.temporal.imagePca() && !layers.empty())
    throw std::invalid_argument("--temporal pca with --layers: each frame is rebuilt from the bottom layer's direct "
                                "and indirect light, so the layers above it would be lost");
  if (const auto able = backendsDeclaring("temporal");
      options.temporal.inBackend() && std::find(able.begin(), able.end(), options.backend) == able.end())
    throw std::invalid_argument("--temporal " + method + " runs in the path tracer's photon pass: it needs " +
                                backendChoice(able));
  if (const auto able = backendsDeclaring("history");
      options.temporal.reprojects() && std::find(able.begin(), able.end(), options.backend) == able.end())
    throw std::invalid_argument("--temporal reproject carries the path tracer's samples from frame to frame: it "
                                "needs " +
                                backendChoice(able));
  return options;
}

// The closing line of --temporal pca: frames written, time spent, windows and modes.
void reportPca(const RenderJob& options, const SequenceOptions& sequence, const TemporalPcaSequence& pca,
               const HighSampleFrames* high, double renderSeconds) {
  std::cout << "wrote " << sequence.frames << " frames " << framePath(options.output, 0) << ".. (rendering "
            << renderSeconds << " s, pca " << pca.denoiseSeconds() << " s in " << pca.windows() << " window(s), "
            << pca.meanModes() << " modes on average"
            << (high
                    ? ", " + std::to_string(high->pixelsRendered()) + " pixels re-rendered at " +
                          std::to_string(options.temporal.highSpp) + " spp in " + std::to_string(high->seconds()) + " s"
                    : std::string())
            << ")\n";
}

}  // namespace

// In steps: the job settled for the scene, the renderer (here, or on the
// nodes), then frames posed, rendered and written in order (through the
// temporal PCA when it is on), and the statistics.
int renderSequence(const RenderJob& given, const SequenceOptions& sequence, const std::vector<LayerSpec>& layers) {
  SceneSession session;
  session.load(given.scene, given.import, given.view);
  RenderJob options = sequenceJob(given, session, layers);
  const std::string method = temporalName(options.temporal);
  // A cluster without layers renders the whole window on the nodes; one
  // whose viewports look ahead (photons) is a layer of a window here, which
  // sends the nodes every frame ahead of the one shown.
  std::vector<LayerSpec> windowLayers = layers;
  if (!sequence.cluster.empty() && layers.empty() && options.temporal.inBackend())
    windowLayers.push_back(LayerSpec{options.backend, "", {}});
  const bool local = sequence.cluster.empty() || !windowLayers.empty();
  if (!sequence.cluster.empty() && local && !options.statsJson.empty())
    throw std::invalid_argument("--stats-json with --cluster and --temporal " + method +
                                ": the nodes render one layer of a window here, which keeps no per-node figures");
  med::RenderStats stats;
  ClusterStatsLog clusterStats;
  // The bar moves with the cluster's tiles within a frame, not only between frames.
  double framesShown = 0;
  std::function<void(double)> onTiles;
  SequenceRenderer renderer = local ? localRenderer(options, windowLayers, session, stats)
                                    : SequenceRenderer{clusterRenderer(options, session, clusterStats,
                                                                       [&](double share) {
                                                                         if (onTiles) onTiles(share);
                                                                       }),
                                                       0,
                                                       {}};
  auto write = [&](int frame, const med::FrameBuffer& image) {
    std::string path = framePath(options.output, frame);
    med::writeImage(path, image, "colour", options.display);
    for (const auto& aov : options.aovs) med::writeImage(aovPath(path, aov), image, aov, aovDisplay(options, aov));
    return path;
  };
  ProgressBar bar(options.temporal.active() ? "rendering + " + method : "rendering", !options.quiet);
  onTiles = [&](double share) { bar.update((framesShown + share) / sequence.frames); };
  std::unique_ptr<HighSampleFrames> high;
  if (options.temporal.highSpp) high = std::make_unique<HighSampleFrames>(options, session);
  std::unique_ptr<TemporalPcaSequence> pca;
  if (options.temporal.imagePca())
    pca = std::make_unique<TemporalPcaSequence>(
        options.temporal, [&](int frame, const med::FrameBuffer& image) { write(frame, image); },
        high ? TemporalPcaSequence::HighSamples(
                   [&](int frame, const std::vector<bool>& need) { return high->render(frame, need); })
             : TemporalPcaSequence::HighSamples());
  double renderSeconds = 0;
  // With a lookahead, frames are posed and committed `lookahead` frames
  // before they are shown: their change lists reach a second replica (the
  // scene ahead) at once and the shown one when their frame's turn comes.
  const int lookahead = static_cast<int>(renderer.lookahead);
  sg::Replica ahead;
  std::deque<sg::ChangeListPtr> pending;
  for (int posed = 0; posed < sequence.frames + lookahead; ++posed) {
    sg::ChangeListPtr delta;
    if (posed < sequence.frames) {
      // Frame 0 is the scene as loaded; later ones pose the animation at
      // frame / fps (with its motion over the frame, for an open shutter).
      if (sequence.framesGiven) session.poseAnimations(posed / sequence.fps, 1.0 / sequence.fps);
      if (lookahead == 0) {
        delta = session.publish();
        if (high) high->follow(posed, delta);
      } else {
        pending.push_back(session.commit());
        ahead.apply(pending.back());
        renderer.prepare(ahead, posed);
      }
    }
    const int frame = posed - lookahead;
    if (frame < 0) continue;
    if (lookahead > 0) {
      delta = pending.front();
      pending.pop_front();
      session.replica.apply(delta);
    }
    const auto* camera = session.replica.scene().find<sg::Camera>(session.camera);
    auto view = med::View::fromCamera(*camera, options.width, options.height);
    auto started = std::chrono::steady_clock::now();
    med::FrameBuffer image = renderer.render(session, delta, view, frame);
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    renderSeconds += seconds;
    if (pca) {
      pca->add(frame, std::move(image));
    } else {
      std::string path = write(frame, image);
      if (!options.quiet && !bar.active())
        std::cout << "wrote " << path << " (" << image.width << "x" << image.height << ", " << seconds << " s)\n";
    }
    framesShown = frame + 1;
    bar.update(framesShown / sequence.frames);
  }
  if (pca) {
    pca->finish();
    bar.finish();
    if (!options.quiet) reportPca(options, sequence, *pca, high.get(), renderSeconds);
  }
  if (!options.statsJson.empty()) {
    if (local)
      writeStatsJson(options, stats, sequence.frames);
    else
      clusterStats.write(options);
  }
  return 0;
}

}  // namespace tsr::app
