// visibility=all against visibility=guided on one scene, through the Vulkan
// viewport as an application drives it (both viewports share the converted
// scene). A comparison program, not a timed test:
//   guided_compare [SCENE] [WIDTHxHEIGHT] [FRAMES]
// (default builtin:plant:5000000 960x540 5). For views inside and outside
// the model it prints the median frame time of each mode over FRAMES still
// frames, the triangles and objects each draws, the pixels that differ on
// the first guided frame from a view and on the still frames after it, and
// for a walk along the aisle (a moving camera) the largest difference of
// any frame.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/scene_session.hpp"
#include "tsr/med/scene_flattening.hpp"
#include "tsr/med/vulkan/register.hpp"
#include "tsr/sg/node_world.hpp"
#include "vulkan_viewport.hpp"

namespace {

using namespace tsr;

struct Frame {
  double seconds = 0;
  vk::RenderStats counts;
};

struct Mode {
  std::unique_ptr<med::Viewport> viewport;
  med::FrameBuffer image;
  Frame render(const sg::Replica& replica, const med::View& view) {
    const med::RenderStats s = viewport->render(replica, view, image);
    return {s.seconds, dynamic_cast<const med::vulkan_mediator::VulkanViewport&>(*viewport).lastFrame()};
  }
};

std::size_t differing(const med::FrameBuffer& a, const med::FrameBuffer& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.colour.size(); ++i) n += a.colour[i] != b.colour[i];
  return n;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// World bounds of everything the root shows.
std::pair<glm::vec3, glm::vec3> bounds(const sg::Scene& scene, sg::ContainerId root) {
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const med::FlatNode& n : med::flatten(scene, root).instances)
    if (const auto* g = scene.find<sg::Geometry>(n.id))
      for (const auto& p : g->positions()) {
        const glm::vec3 w(n.world * glm::vec4(p, 1.0f));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
      }
  return {lo, hi};
}

med::View looking(med::View v, glm::vec3 eye, glm::vec3 target) {
  v.cameraToWorld = glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0)));
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string sceneName = argc > 1 ? argv[1] : "builtin:plant:5000000";
  std::uint32_t width = 960, height = 540;
  if (argc > 2 && std::sscanf(argv[2], "%ux%u", &width, &height) != 2) return std::fprintf(stderr, "bad size\n"), 2;
  const int frames = argc > 3 ? std::max(1, std::atoi(argv[3])) : 5;

  app::SceneSession session;
  session.load(sceneName);
  session.publish();
  const sg::Scene& scene = session.replica.scene();
  med::ViewportRegistry registry;
  med::registerVulkan(registry);
  med::ContextPool contexts;
  med::Parameters guidedParameters;
  guidedParameters.set("visibility", std::string("guided"));
  Mode full{registry.create({"vulkan", session.imported.root, session.imported.background, {}, true}, contexts), {}};
  Mode guided{
      registry.create({"vulkan", session.imported.root, session.imported.background, guidedParameters, true}, contexts),
      {}};

  const med::View inside = med::View::fromCamera(*scene.find<sg::Camera>(session.camera), width, height);
  const auto [lo, hi] = bounds(scene, session.imported.root);
  const glm::vec3 centre = 0.5f * (lo + hi), size = hi - lo;
  const glm::vec3 ahead = glm::vec3(inside.cameraToWorld[3]) + glm::vec3(0, 0, 0.25f * size.z);
  struct Named {
    const char* name;
    med::View view;
  };
  const Named views[] = {
      {"inside, down the aisle", inside},
      {"inside, turned 60 deg", looking(inside, ahead, ahead + glm::vec3(0.87f, 0, 0.5f))},
      {"outside, above a corner",
       looking(inside, lo + glm::vec3(-0.1f, 0.0f, -0.1f) * size + glm::vec3(0, 30, 0), centre)},
      {"outside, from the side", looking(inside, glm::vec3(lo.x - 20, 5, centre.z), centre)},
  };
  full.render(session.replica, inside);  // conversion, not measured
  const auto& vkScene =
      dynamic_cast<const med::vulkan_mediator::VulkanViewport&>(*full.viewport).context().adapter.scene();
  const std::uint64_t sceneTriangles = full.render(session.replica, inside).counts.triangles;
  std::printf("geometry held by the rasterizer: %.1f MB for %llu triangles, %.1f bytes per triangle\n",
              double(vkScene.geometryBytesHeld()) / 1e6, static_cast<unsigned long long>(sceneTriangles),
              double(vkScene.geometryBytesHeld()) / double(std::max<std::uint64_t>(sceneTriangles, 1)));
  std::printf("%s, %ux%u, %d still frames per view (median)\n", sceneName.c_str(), width, height, frames);
  std::printf("%-24s | %9s %11s %7s | %9s %11s %7s | %7s | %10s %10s\n", "view", "full ms", "triangles", "objects",
              "guided ms", "triangles", "objects", "ratio", "diff first", "diff still");
  for (const Named& v : views) {
    full.render(session.replica, v.view);
    const Frame first = guided.render(session.replica, v.view);
    const std::size_t diffFirst = differing(full.image, guided.image);
    std::vector<double> fullTimes, guidedTimes;
    std::size_t diffStill = 0;
    Frame f, g;
    for (int i = 0; i < frames; ++i) {
      f = full.render(session.replica, v.view);
      fullTimes.push_back(f.seconds);
      g = guided.render(session.replica, v.view);
      guidedTimes.push_back(g.seconds);
      diffStill = std::max(diffStill, differing(full.image, guided.image));
    }
    const double fm = median(fullTimes) * 1e3, gm = median(guidedTimes) * 1e3;
    std::printf("%-24s | %9.1f %11llu %7u | %9.1f %11llu %7u | %6.1fx | %10zu %10zu\n", v.name, fm,
                static_cast<unsigned long long>(f.counts.triangles), f.counts.objects, gm,
                static_cast<unsigned long long>(g.counts.triangles), g.counts.objects, fm / gm, diffFirst, diffStill);
    (void)first;
  }

  // A walk down the aisle, a metre a frame: every guided frame against the full one.
  std::size_t worst = 0, framesDiffering = 0;
  std::vector<double> fullTimes, guidedTimes;
  std::uint64_t lateObjects = 0;
  for (int i = 0; i < 4 * frames; ++i) {
    const med::View v =
        looking(inside, glm::vec3(inside.cameraToWorld[3]) + glm::vec3(0, 0, float(i)),
                glm::vec3(inside.cameraToWorld[3]) + glm::vec3(0.2f * float(i % 5) - 0.4f, 0, float(i) + 10));
    fullTimes.push_back(full.render(session.replica, v).seconds);
    const Frame g = guided.render(session.replica, v);
    guidedTimes.push_back(g.seconds);
    lateObjects += g.counts.lateObjects;
    const std::size_t d = differing(full.image, guided.image);
    worst = std::max(worst, d);
    framesDiffering += d > 0;
  }
  std::printf("walk, %d frames, 1 m/frame: full %.1f ms, guided %.1f ms (median), %.1f objects/frame found late, "
              "%zu frames differ, at most %zu pixels\n",
              4 * frames, median(fullTimes) * 1e3, median(guidedTimes) * 1e3, double(lateObjects) / (4 * frames),
              framesDiffering, worst);
  return worst == 0 ? 0 : 1;
}
