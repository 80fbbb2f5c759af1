// What a browser must load to show 95 % of a view's covered pixels: the
// culling service's set (objects ranked by visible coverage, occlusion
// included) against what a three.js user has without a service — frustum
// culling plus loading by projected size, as 3D Tiles' screen-space error
// does, which also loads what is hidden behind other objects.
//   cull_compare [SCENE] [WIDTHxHEIGHT] [SHARE]
// (default builtin:plant:5000000 960x540 0.95: the share of covered pixels)
// For three views from the scene's camera (turned 0, 60 and 120 degrees)
// it prints the triangles each method loads and their ratio.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unordered_map>

#include <glm/gtc/matrix_transform.hpp>

#include "backends.hpp"
#include "scene/scene_session.hpp"
#include "tsr/med/coverage/ranking.hpp"
#include "tsr/med/scene_flattening.hpp"
#include "tsr/sg/node_world.hpp"

namespace {

using namespace tsr;

struct ObjectInfo {
  glm::vec3 lo{1e30f}, hi{-1e30f};
  std::uint64_t triangles = 0;
};

// True unless every corner of the box lies outside one side of the view's frustum.
bool inFrustum(const med::View& view, const ObjectInfo& o) {
  const glm::mat4 worldToCamera = glm::inverse(view.cameraToWorld);
  int outside[6] = {0, 0, 0, 0, 0, 0};
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 corner((c & 1) ? o.hi.x : o.lo.x, (c & 2) ? o.hi.y : o.lo.y, (c & 4) ? o.hi.z : o.lo.z);
    const glm::vec3 p = glm::vec3(worldToCamera * glm::vec4(corner, 1.0f));
    const float depth = -p.z;
    outside[0] += depth < view.nearPlane;
    outside[1] += depth > view.farPlane;
    outside[2] += p.x < view.left / view.nearPlane * depth;
    outside[3] += p.x > view.right / view.nearPlane * depth;
    outside[4] += p.y < view.bottom / view.nearPlane * depth;
    outside[5] += p.y > view.top / view.nearPlane * depth;
  }
  return std::none_of(std::begin(outside), std::end(outside), [](int n) { return n == 8; });
}

// The screen-space size a tiles renderer loads by: the bounding sphere's
// radius over its distance.
double projectedSize(const med::View& view, const ObjectInfo& o) {
  const glm::vec3 eye = glm::vec3(view.cameraToWorld[3]);
  const glm::vec3 centre = 0.5f * (o.lo + o.hi);
  const double radius = 0.5 * glm::length(o.hi - o.lo);
  return radius / std::max(1e-6, double(glm::length(centre - eye)) - radius);
}

// Triangles of the shortest prefix of `order` whose visible pixels reach
// 95 % of the covered pixels; and how many objects that took.
std::pair<std::uint64_t, std::size_t> needed(const std::vector<sg::ContainerId>& order,
                                             const std::unordered_map<sg::ContainerId, std::uint64_t>& visible,
                                             const std::unordered_map<sg::ContainerId, ObjectInfo>& objects,
                                             std::uint64_t covered, double share) {
  std::uint64_t pixels = 0, triangles = 0;
  std::size_t n = 0;
  for (sg::ContainerId id : order) {
    if (pixels >= share * double(covered)) break;
    auto v = visible.find(id);
    pixels += v == visible.end() ? 0 : v->second;
    triangles += objects.at(id).triangles;
    ++n;
  }
  return {triangles, n};
}

}  // namespace

int main(int argc, char** argv) {
  const std::string sceneName = argc > 1 ? argv[1] : "builtin:plant:5000000";
  std::uint32_t width = 960, height = 540;
  if (argc > 2 && std::sscanf(argv[2], "%ux%u", &width, &height) != 2) return std::fprintf(stderr, "bad size\n"), 2;
  const double share = argc > 3 ? std::atof(argv[3]) : 0.95;
  if (!(share > 0 && share <= 1)) return std::fprintf(stderr, "SHARE: a fraction in (0, 1]\n"), 2;
  app::SceneSession session;
  session.load(sceneName);
  session.publish();
  const sg::Scene& scene = session.replica.scene();
  std::unordered_map<sg::ContainerId, ObjectInfo> objects;
  std::uint64_t total = 0;
  for (const med::FlatNode& instance : med::flatten(scene, session.imported.root).instances) {
    const auto* g = scene.find<sg::Geometry>(instance.id);
    if (!g) continue;
    ObjectInfo& o = objects[med::objectOf(scene, instance)];
    o.triangles += g->triangleCount();
    total += g->triangleCount();
    for (const auto& p : g->positions()) {
      const glm::vec3 w = glm::vec3(instance.world * glm::vec4(p, 1.0f));
      o.lo = glm::min(o.lo, w);
      o.hi = glm::max(o.hi, w);
    }
  }
  med::ViewportRegistry registry;
  app::registerBackends(registry);
  med::ContextPool contexts;
  auto viewport = registry.create({"coverage", session.imported.root, session.imported.background, {}, true}, contexts);
  std::printf("%s: %zu objects, %llu triangles, %ux%u, loaded until %.0f %% of the covered pixels show\n",
              sceneName.c_str(), objects.size(), static_cast<unsigned long long>(total), width, height, share * 100);
  std::printf("%-6s %8s %10s | %22s | %22s | %6s\n", "view", "seen", "in frustum", "coverage-ranked (objs)",
              "frustum+size (objs)", "ratio");
  const auto* camera = scene.find<sg::Camera>(session.camera);
  for (float yaw : {0.0f, 60.0f, 120.0f}) {
    sg::Camera turned;
    turned.setNearPlane(camera->nearPlane());
    turned.setFarPlane(camera->farPlane());
    turned.setVerticalFov(camera->verticalFov());
    turned.setPose(sg::cameraWorldPose(scene, session.camera) *
                   glm::rotate(glm::mat4(1.0f), glm::radians(yaw), glm::vec3(0, 1, 0)));
    const med::View view = med::View::fromCamera(turned, width, height);
    med::FrameBuffer image;
    med::RenderControl control;
    control.outputs = std::vector<std::string>{med::kIdOutput};
    viewport->render(session.replica, view, image, control);
    std::unordered_map<sg::ContainerId, std::uint64_t> visible;
    std::vector<sg::ContainerId> byCoverage, bySize;
    std::uint64_t covered = 0;
    for (const auto& r : med::rankObjects(image, scene)) {
      visible[r.id] = r.pixels;
      covered += r.pixels;
      byCoverage.push_back(r.id);
    }
    for (const auto& [id, o] : objects)
      if (inFrustum(view, o)) bySize.push_back(id);
    std::sort(bySize.begin(), bySize.end(), [&](sg::ContainerId a, sg::ContainerId b) {
      const double sa = projectedSize(view, objects.at(a)), sb = projectedSize(view, objects.at(b));
      return sa != sb ? sa > sb : a < b;
    });
    const auto [coverageTriangles, coverageObjects] = needed(byCoverage, visible, objects, covered, share);
    const auto [sizeTriangles, sizeObjects] = needed(bySize, visible, objects, covered, share);
    std::printf("%4.0f° %8zu %10zu | %12llu (%6zu) | %12llu (%6zu) | %5.1fx\n", yaw, byCoverage.size(), bySize.size(),
                static_cast<unsigned long long>(coverageTriangles), coverageObjects,
                static_cast<unsigned long long>(sizeTriangles), sizeObjects,
                coverageTriangles ? double(sizeTriangles) / double(coverageTriangles) : 0.0);
  }
  return 0;
}
