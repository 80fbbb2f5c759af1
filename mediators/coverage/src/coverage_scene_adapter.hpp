#pragma once
// The coverage pass's scene adapter: the shared instancing adapter with the
// id renderer (seen as an IdScene) and the id pass's translations. Meshes
// hold positions and topology only, so normal, uv and colour edits cost
// nothing here; a material matters only as "transparent or not".
#include <limits>
#include <optional>

#include <spdlog/spdlog.h>

#include "id_scene.hpp"
#include "translation.hpp"
#include "tsr/cov/error.hpp"
#include "tsr/med/instancing_scene_adapter.hpp"

namespace tsr::med::coverage_mediator {

struct CoverageTypes {
  using Device = IdRendererSource;
  using Scene = IdScene;
  using Environment = NoEnvironment;
  using Error = cov::Error;
  static constexpr const char* kName = "coverage";
  static constexpr sg::FieldMask kMeshFields =
      sg::fieldBit(sg::Geometry::Positions) | sg::fieldBit(sg::Geometry::Indices) | sg::fieldBit(sg::Geometry::Motion) |
      sg::fieldBit(sg::Geometry::Primitive);
  static constexpr bool kResizableMeshes = true;
  // Which id renderer draws them is chosen at run time: one that cannot refuses the mesh.
  static constexpr bool kLinesAndPoints = true;
  static cov::MeshData mesh(const sg::Geometry& g) { return translateMesh(g); }
  // A medium-only object (a volume with no surface) is as transparent as glass.
  template <class Textures>
  static Transparency material(const sg::Container* m, const sg::VolumeMaterial* volume, const Textures&) {
    return {isTransparent(m) || (volume && !m)};
  }
  static NoTexture texture(const sg::Image&) { return {}; }
  static NoEnvironment background(const sg::Scene&, sg::ContainerId) { return {}; }
  // What the instance's pixels report: see objectOf.
  static std::optional<cov::ObjectId> object(const sg::Scene& scene, const FlatNode& node) {
    const sg::ContainerId object = objectOf(scene, node);
    if (object > std::numeric_limits<cov::ObjectId>::max()) {
      spdlog::warn("coverage: object id {} does not fit 32 bits; skipped", object);
      return std::nullopt;
    }
    return static_cast<cov::ObjectId>(object);
  }
};

using CoverageSceneAdapter = InstancingSceneAdapter<CoverageTypes>;

}  // namespace tsr::med::coverage_mediator
