#pragma once
// A scene as plain data, checked and complete, before any container exists.
// Importers and built-in scenes fill one; buildScene turns it into
// containers in one step that cannot fail on the data.
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tsr/sg/array_elements.hpp"
#include "tsr/sg/geometry.hpp"
#include "tsr/sg/image.hpp"
#include "tsr/sg/import/animation.hpp"
#include "tsr/sg/light.hpp"
#include "tsr/sg/surface_material.hpp"

namespace tsr::sg::parsed {

inline constexpr int kNone = -1;
// A 3D texture is at most this many slices (each at least one row).
inline constexpr std::uint32_t kMaxTextureSlices = 4096;

struct Image {
  std::string name;
  std::string uri;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t channels = 4;
  std::vector<std::uint8_t> pixels;
  ColorSpace colorSpace = ColorSpace::SRGB;
};

// A VolumeMaterial's values (KHR_materials_volume's attenuation as
// absorption, TSR_materials_volume or TSR_scene_medium for the rest).
struct Volume {
  Vec3 emission{0.0f};
  Vec3 absorption{0.0f};
  Vec3 scattering{0.0f};
  float phaseG = 0.0f;
  // Images of 3D textures (TSR_materials_volume): textureSlices slices
  // stacked top to bottom, as sg::VolumeMaterial reads them.
  int absorptionImage = kNone;
  int scatteringImage = kNone;
  int emissionImage = kNone;
  std::uint32_t textureSlices = 1;
};

struct Material {
  std::string name;
  Vec3 baseColor{1.0f};
  float opacity = 1.0f;
  int baseColorImage = kNone;
  float metallic = 1.0f;
  float roughness = 1.0f;
  int metallicRoughnessImage = kNone;
  Vec3 emission{0.0f};
  float emissionStrength = 1.0f;
  int emissionImage = kNone;
  float transmission = 0.0f;
  int transmissionImage = kNone;
  float ior = 1.5f;
  int normalImage = kNone;
  float normalScale = 1.0f;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  int occlusionImage = kNone;
  float occlusionStrength = 1.0f;
  // Empty, or SurfaceMaterial::kUvTransformRows rows (KHR_texture_transform).
  std::vector<Vec3> uvTransforms;
  std::optional<Volume> volume;  // what fills a closed mesh of this material
};

// A mesh's arrays in place where a converted-scene cache entry was mapped
// (each holds the mapping): a cached load copies no bulk geometry.
struct HeldArrays {
  std::shared_ptr<const ArrayElements<Vec3>> positions;
  std::shared_ptr<const ArrayElements<Vec3>> normals;
  std::shared_ptr<const ArrayElements<Vec2>> uvs;
  std::shared_ptr<const ArrayElements<Vec4>> colors;
  std::shared_ptr<const ArrayElements<std::uint32_t>> indices;
};

// A mesh's arrays to read, wherever they are.
struct ArrayViews {
  std::span<const Vec3> positions;
  std::span<const Vec3> normals;
  std::span<const Vec2> uvs;
  std::span<const Vec4> colors;
  std::span<const std::uint32_t> indices;
};

// One triangle mesh: what a Geometry container holds.
struct Primitive {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<Vec2> uvs;
  std::vector<Vec4> colors;
  std::vector<std::uint32_t> indices;  // a list of primitive's
  // Set by a cache hit instead of the vectors above, which then stay empty.
  std::optional<HeldArrays> held;
  GeometryPrimitive primitive = GeometryPrimitive::Triangles;
  int material = kNone;  // kNone: the default material
  bool animated = false;

  ArrayViews arrays() const {
    if (!held) return {positions, normals, uvs, colors, indices};
    return {elementsOf(held->positions), elementsOf(held->normals), elementsOf(held->uvs), elementsOf(held->colors),
            elementsOf(held->indices)};
  }
};

struct Mesh {
  std::string name;
  std::vector<int> primitives;
};

struct Light {
  std::string name;
  LightKind kind = LightKind::Point;
  Vec3 color{1.0f};
  float intensity = 1.0f;
  float innerCone = 0.0f;
  float outerCone = 0.7853982f;
};

struct Camera {
  std::string name;
  float yfov = 0.7853982f;
  float znear = 0.1f;
  float zfar = 1000.0f;
  // TSR_camera_lens: a thin lens (0: a pinhole, what glTF itself describes).
  float apertureRadius = 0.0f;
  float focusDistance = 5.0f;
};

struct Node {
  std::string name;
  Mat4 local{1.0f};
  // Set when the source gave TRS; animations start from it.
  std::optional<Animation::Pose> trs;
  std::vector<int> children;
  int mesh = kNone;
  int light = kNone;
  int camera = kNone;
};

// Channels name nodes by index; buildScene maps them to Transform ids.
struct AnimationChannel {
  int node = kNone;
  Animation::Path path = Animation::Path::Translation;
  Animation::Interpolation interpolation = Animation::Interpolation::Linear;
  std::vector<float> times;
  std::vector<Vec4> values;
};

struct AnimationClip {
  std::string name;
  bool looping = false;
  std::vector<AnimationChannel> channels;
};

struct Scene {
  std::vector<Image> images;
  std::vector<Material> materials;
  std::vector<Primitive> primitives;
  std::vector<Mesh> meshes;
  std::vector<Light> lights;
  std::vector<Camera> cameras;
  std::vector<Node> nodes;
  std::vector<int> roots;
  std::vector<AnimationClip> animations;
  Vec3 background{0.0f};
  // The length of one scene unit: glTF's are metres; the built-in Cornell
  // box keeps its classic millimetres.
  float metresPerUnit = 1.0f;
  std::optional<Volume> medium;  // fog filling the scene outside every volume
  std::vector<std::string> warnings;
  std::size_t skippedPrimitives = 0;
  // The source named other files (buffers, images): its own bytes do not
  // say everything it holds, so the converted-scene cache skips it.
  bool readOtherFiles = false;
};

}  // namespace tsr::sg::parsed

namespace tsr::sg {
class Scene;
struct ImportResult;
// Creates the containers of a checked parsed scene, taking its vertex
// arrays and pixels (so the bulk is held once while it is built).
ImportResult buildScene(Scene& scene, parsed::Scene&& data);
}  // namespace tsr::sg
