#include <functional>

#include "parsed_scene.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::sg {
namespace {

// Creates containers on first use, so nothing the scene graph does not
// reach (unused materials, images, nodes outside the scene) is created.
class Builder {
 public:
  Builder(Scene& scene, parsed::Scene& data, ImportResult& result) : scene_(scene), data_(data), result_(result) {
    images_.assign(data.images.size(), kNoContainer);
    materials_.assign(data.materials.size(), kNoContainer);
    volumes_.assign(data.materials.size(), kNoContainer);
    geometries_.assign(data.primitives.size(), kNoContainer);
    lights_.assign(data.lights.size(), kNoContainer);
    transforms_.assign(data.nodes.size(), kNoContainer);
  }

  void build() {
    Group& root = scene_.create<Group>("import root");
    result_.root = root.id();
    std::vector<ContainerId> top;
    for (int r : data_.roots) top.push_back(node(r));
    root.setChildren(std::move(top));

    Background& bg = scene_.create<Background>("background");
    bg.setColor(data_.background);
    if (data_.medium) bg.setMedium(volume(*data_.medium, "scene medium"));
    result_.background = bg.id();

    for (const parsed::AnimationClip& clip : data_.animations) animation(clip);
    result_.warnings = data_.warnings;
    result_.counts.skippedPrimitives = data_.skippedPrimitives;
  }

 private:
  ContainerId node(int index) {
    const parsed::Node& n = data_.nodes[static_cast<std::size_t>(index)];
    Transform& t = scene_.create<Transform>(n.name);
    t.setMatrix(n.local);
    transforms_[static_cast<std::size_t>(index)] = t.id();
    ++result_.counts.nodes;

    std::vector<ContainerId> children;
    if (n.mesh != parsed::kNone)
      for (int p : data_.meshes[static_cast<std::size_t>(n.mesh)].primitives) children.push_back(geometry(p));
    if (n.light != parsed::kNone) children.push_back(light(n.light));
    if (n.camera != parsed::kNone) children.push_back(camera(n.camera));
    for (int c : n.children) children.push_back(node(c));
    t.setChildren(std::move(children));
    return t.id();
  }

  ContainerId geometry(int index) {
    ContainerId& id = geometries_[static_cast<std::size_t>(index)];
    if (id != kNoContainer) return id;
    // Each primitive becomes one geometry (once, above), which takes its arrays.
    parsed::Primitive& p = data_.primitives[static_cast<std::size_t>(index)];
    Geometry& g = scene_.create<Geometry>();
    if (p.held) {
      g.setSharedPositions(SharedArray<Vec3>(std::move(p.held->positions)));
      g.setSharedNormals(SharedArray<Vec3>(std::move(p.held->normals)));
      g.setSharedUvs(SharedArray<Vec2>(std::move(p.held->uvs)));
      g.setSharedColors(SharedArray<Vec4>(std::move(p.held->colors)));
      g.setSharedIndices(SharedArray<std::uint32_t>(std::move(p.held->indices)));
    } else {
      g.setPositions(std::move(p.positions));
      g.setNormals(std::move(p.normals));
      g.setUvs(std::move(p.uvs));
      g.setColors(std::move(p.colors));
      g.setIndices(std::move(p.indices));
    }
    g.setPrimitive(p.primitive);
    g.setMaterial(material(p.material));
    if (p.material != parsed::kNone) {
      const auto m = static_cast<std::size_t>(p.material);
      if (const auto& v = data_.materials[m].volume) {
        if (volumes_[m] == kNoContainer) volumes_[m] = volume(*v, data_.materials[m].name + " volume");
        g.setVolume(volumes_[m]);
      }
    }
    if (p.animated) g.setMotion(GeometryMotion::Animated);
    ++result_.counts.geometries;
    result_.counts.uniqueTriangles += g.triangleCount();
    return id = g.id();
  }

  ContainerId material(int index) {
    if (index == parsed::kNone) {
      // glTF's default material: white, fully metallic and rough.
      if (defaultMaterial_ == kNoContainer) {
        parsed::Material gltfDefault;
        gltfDefault.name = "default";
        defaultMaterial_ = surface(gltfDefault);
      }
      return defaultMaterial_;
    }
    ContainerId& id = materials_[static_cast<std::size_t>(index)];
    if (id == kNoContainer) id = surface(data_.materials[static_cast<std::size_t>(index)]);
    return id;
  }

  ContainerId surface(const parsed::Material& m) {
    SurfaceMaterial& s = scene_.create<SurfaceMaterial>(m.name);
    s.setBaseColor(m.baseColor);
    s.setOpacity(m.opacity);
    s.setMetallic(m.metallic);
    s.setRoughness(m.roughness);
    s.setEmission(m.emission);
    s.setEmissionStrength(m.emissionStrength);
    s.setTransmission(m.transmission);
    s.setIor(m.ior);
    s.setNormalScale(m.normalScale);
    if (m.baseColorImage != parsed::kNone) s.setBaseColorTexture(image(m.baseColorImage));
    if (m.metallicRoughnessImage != parsed::kNone) s.setMetallicRoughnessTexture(image(m.metallicRoughnessImage));
    if (m.emissionImage != parsed::kNone) s.setEmissionTexture(image(m.emissionImage));
    if (m.transmissionImage != parsed::kNone) s.setTransmissionTexture(image(m.transmissionImage));
    if (m.normalImage != parsed::kNone) s.setNormalTexture(image(m.normalImage));
    if (m.occlusionImage != parsed::kNone) s.setOcclusionTexture(image(m.occlusionImage));
    s.setOcclusionStrength(m.occlusionStrength);
    s.setAlphaMode(m.alphaMode);
    s.setAlphaCutoff(m.alphaCutoff);
    if (!m.uvTransforms.empty()) s.setUvTransforms(m.uvTransforms);
    ++result_.counts.materials;
    return s.id();
  }

  ContainerId volume(const parsed::Volume& v, const std::string& name) {
    VolumeMaterial& m = scene_.create<VolumeMaterial>(name);
    m.setEmission(v.emission);
    m.setAbsorption(v.absorption);
    m.setScattering(v.scattering);
    m.setPhaseG(v.phaseG);
    m.setTextureSlices(v.textureSlices);
    if (v.absorptionImage != parsed::kNone) m.setAbsorptionTexture(image(v.absorptionImage));
    if (v.scatteringImage != parsed::kNone) m.setScatteringTexture(image(v.scatteringImage));
    if (v.emissionImage != parsed::kNone) m.setEmissionTexture(image(v.emissionImage));
    return m.id();
  }

  ContainerId image(int index) {
    ContainerId& id = images_[static_cast<std::size_t>(index)];
    if (id != kNoContainer) return id;
    parsed::Image& src = data_.images[static_cast<std::size_t>(index)];
    Image& img = scene_.create<Image>(src.name);
    img.setPixels(src.width, src.height, src.channels, PixelFormat::UInt8, std::move(src.pixels));
    img.setColorSpace(src.colorSpace);
    if (!src.uri.empty()) img.setUri(src.uri);
    ++result_.counts.images;
    return id = img.id();
  }

  ContainerId light(int index) {
    ContainerId& id = lights_[static_cast<std::size_t>(index)];
    if (id != kNoContainer) return id;
    const parsed::Light& src = data_.lights[static_cast<std::size_t>(index)];
    Light& l = scene_.create<Light>(src.name);
    l.setKind(src.kind);
    l.setColor(src.color);
    l.setIntensity(src.intensity);
    l.setInnerConeAngle(src.innerCone);
    l.setOuterConeAngle(src.outerCone);
    result_.lights.push_back(l.id());
    return id = l.id();
  }

  // A child of its node, so the node's (animated) transforms move it.
  ContainerId camera(int index) {
    const parsed::Camera& src = data_.cameras[static_cast<std::size_t>(index)];
    Camera& c = scene_.create<Camera>(src.name);
    c.setVerticalFov(src.yfov);
    c.setNearPlane(src.znear);
    c.setFarPlane(src.zfar);
    c.setApertureRadius(src.apertureRadius);
    c.setFocusDistance(src.focusDistance);
    // Stereo defaults are lengths in metres (eyes 65 mm apart).
    c.setEyeSeparation(c.eyeSeparation() / data_.metresPerUnit);
    c.setZeroParallaxDistance(c.zeroParallaxDistance() / data_.metresPerUnit);
    result_.cameras.push_back(c.id());
    return c.id();
  }

  void animation(const parsed::AnimationClip& clip) {
    Animation anim(clip.name);
    anim.setLooping(clip.looping);
    bool any = false;
    for (const parsed::AnimationChannel& ch : clip.channels) {
      ContainerId target = transforms_[static_cast<std::size_t>(ch.node)];
      if (target == kNoContainer) continue;  // a node outside the imported scene
      const parsed::Node& n = data_.nodes[static_cast<std::size_t>(ch.node)];
      anim.setRestPose(target, n.trs.value_or(Animation::Pose{}));
      anim.addChannel({target, ch.path, ch.interpolation, ch.times, ch.values});
      any = true;
    }
    if (any) result_.animations.push_back(std::move(anim));
  }

  Scene& scene_;
  parsed::Scene& data_;
  ImportResult& result_;
  std::vector<ContainerId> images_, materials_, volumes_, geometries_, lights_, transforms_;
  ContainerId defaultMaterial_ = kNoContainer;
};

}  // namespace

ImportResult buildScene(Scene& scene, parsed::Scene&& data) {
  ImportResult result;
  result.metresPerUnit = data.metresPerUnit;
  Builder(scene, data, result).build();
  return result;
}

}  // namespace tsr::sg
