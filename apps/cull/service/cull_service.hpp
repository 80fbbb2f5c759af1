#pragma once
// The culling service's work, apart from HTTP: a view in, the objects that
// cover most of its pixels out (Schwenk, 5.4.3), ranked by the coverage
// renderer over one converted scene; and each object as a standalone glTF
// binary, in world space, for the client to load.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "cull_query.hpp"
#include "scene/scene_session.hpp"
#include "tsr/med/context_pool.hpp"
#include "tsr/med/scene_flattening.hpp"
#include "tsr/med/viewport_registry.hpp"

namespace tsr::app {

class CullService {
 public:
  // Loads the scene (sg::ImportError, std::invalid_argument) and converts it
  // once for `backend` (a back-end offering the "id" output).
  CullService(const std::string& scene, const sg::ImportOptions& import, const std::string& backend,
              const med::Parameters& parameters);

  // Thread-safe; renders are serialised on the one converted scene. A set
  // `cancel` stops the render early (the answer is then meaningless).
  CullAnswer cull(const CullQuery& query, const std::atomic<bool>* cancel = nullptr);
  // The object's geometry under it, in world space, as a .glb; nothing for
  // an id that names no object of the ranking's kind.
  std::optional<std::vector<std::uint8_t>> objectGlb(sg::ContainerId id) const;
  std::uint64_t totalObjects() const { return triangles_.size(); }
  std::uint64_t totalTriangles() const { return totalTriangles_; }

  // The query's pose and field of view at its size, with the near and far
  // planes of the scene's own camera (they fit its scale); CullRequestError
  // for a view no back-end could render.
  med::View viewOf(const CullQuery& query) const;
  // The scene's own camera, as a query would give it (the page starts there).
  CullQuery sceneView() const;
  // What the page shows first: the scene's camera, bounds and totals (JSON).
  std::string sceneJson(bool preview) const;
  // The background as the page can show it (JSON: kind, colour or gradient).
  nlohmann::json backgroundJson() const;
  // Settings of a viewport of `backend` over the service's scene.
  med::ViewportSettings settingsFor(const std::string& backend, const med::Parameters& parameters) const;
  // The one converted scene every viewport here renders; never edited.
  const sg::Replica& replica() const { return session_.replica; }
  med::ContextPool& contexts() { return contexts_; }
  const med::ViewportRegistry& registry() const { return registry_; }

 private:
  SceneSession session_;
  med::ViewportRegistry registry_;
  med::ContextPool contexts_;
  std::unique_ptr<med::Viewport> viewport_;
  std::unordered_map<sg::ContainerId, std::vector<med::FlatNode>> parts_;  // per object: its geometry instances
  std::unordered_map<sg::ContainerId, std::uint64_t> triangles_;           // per object
  std::uint64_t totalTriangles_ = 0;
  glm::vec3 boundsMin_{-1.0f}, boundsMax_{1.0f};  // of the whole scene
  std::mutex mutex_;
};

}  // namespace tsr::app
