#include "translation.hpp"

namespace tsr::med::coverage_mediator {

cov::MeshData translateMesh(const sg::Geometry& geometry) {
  cov::MeshData data;
  data.positions = geometry.positions().toVector();
  data.indices = geometry.indices().toVector();
  data.primitive = primitiveOf(geometry);
  data.usage = geometry.motion() == sg::GeometryMotion::Animated ? cov::MeshUsage::Animated : cov::MeshUsage::Static;
  return data;
}

bool isTransparent(const sg::Container* material) {
  if (!material) return false;
  if (material->type() == sg::ContainerType::SimpleMaterial)
    return static_cast<const sg::SimpleMaterial*>(material)->transparency() > 0.0f;
  if (material->type() == sg::ContainerType::SurfaceMaterial) {
    const auto* s = static_cast<const sg::SurfaceMaterial*>(material);
    return s->opacity() < 1.0f || s->transmission() > 0.5f;
  }
  return false;
}

}  // namespace tsr::med::coverage_mediator
