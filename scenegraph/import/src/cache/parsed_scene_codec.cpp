#include "cache/parsed_scene_codec.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "cache/parsed_scene_validation.hpp"

namespace tsr::sg::parsed {
namespace {

constexpr std::size_t kArrayAlignment = 8;

// Writes through a sink in pieces: a large array goes straight from the
// scene's memory, small values are gathered first, so the whole encoding
// (as large as the scene's arrays) is never held.
class Writer {
 public:
  explicit Writer(const ByteSink& sink) : sink_(sink) {}
  template <class T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes(&v, sizeof(T));
  }
  // Elements start on a multiple of kArrayAlignment, so a mapped entry's
  // arrays can be used in place.
  template <class T>
  void array(std::span<const T> v) {
    static_assert(kArrayAlignment % alignof(T) == 0);
    pod(std::uint64_t(v.size()));
    static constexpr std::uint8_t kZeros[kArrayAlignment] = {};
    bytes(kZeros, (kArrayAlignment - size_ % kArrayAlignment) % kArrayAlignment);
    bytes(v.data(), v.size_bytes());
  }
  template <class T>
  void array(const std::vector<T>& v) {
    array(std::span<const T>(v));
  }
  void text(const std::string& s) {
    pod(std::uint64_t(s.size()));
    bytes(s.data(), s.size());
  }
  void finish() { flush(); }

 private:
  static constexpr std::size_t kGathered = std::size_t(1) << 20;
  void bytes(const void* data, std::size_t n) {
    if (n == 0) return;
    size_ += n;
    const auto* p = static_cast<const std::uint8_t*>(data);
    if (n >= kGathered / 4) {
      flush();
      sink_({p, n});
      return;
    }
    gathered_.insert(gathered_.end(), p, p + n);
    if (gathered_.size() >= kGathered) flush();
  }
  void flush() {
    if (!gathered_.empty()) sink_(gathered_);
    gathered_.clear();
  }
  const ByteSink& sink_;
  std::vector<std::uint8_t> gathered_;
  std::uint64_t size_ = 0;  // bytes written so far: where the next array's padding ends
};

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> in) : in_(in) {}
  template <class T>
  T pod() {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T), "a value");
    T v;
    std::memcpy(&v, in_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  template <class T>
  std::vector<T> array() {
    return copied<T>(arrayBytes(sizeof(T)));
  }
  // An array left where it is, held with `keeper` (which keeps the bytes
  // alive), or copied when the bytes are not aligned for T in memory.
  template <class T>
  std::shared_ptr<const ArrayElements<T>> held(const std::shared_ptr<const void>& keeper) {
    const std::span<const std::uint8_t> bytes = arrayBytes(sizeof(T));
    if (bytes.empty()) return nullptr;
    if (reinterpret_cast<std::uintptr_t>(bytes.data()) % alignof(T) != 0)
      return std::make_shared<const ArrayElements<T>>(copied<T>(bytes));
    const std::span<const T> view(reinterpret_cast<const T*>(bytes.data()), bytes.size() / sizeof(T));
    return std::make_shared<const ArrayElements<T>>(view, keeper);
  }
  std::string text() {
    const std::uint64_t n = count(1);
    std::string s(reinterpret_cast<const char*>(in_.data() + at_), n);
    at_ += n;
    return s;
  }
  // A count of elements (or records) of at least `size` bytes each that
  // must all still be there: nothing is allocated for data that is not.
  std::uint64_t count(std::size_t size) {
    const auto n = pod<std::uint64_t>();
    if (n > (in_.size() - at_) / std::max<std::size_t>(size, 1))
      throw std::runtime_error("an array of " + std::to_string(n) + " elements runs past the end");
    return n;
  }
  template <class T>
  static std::vector<T> copied(std::span<const std::uint8_t> bytes) {
    std::vector<T> v(bytes.size() / sizeof(T));
    if (!v.empty()) std::memcpy(v.data(), bytes.data(), bytes.size());
    return v;
  }
  // An array's count, its zero padding and its elements' bytes.
  std::span<const std::uint8_t> arrayBytes(std::size_t elementSize) {
    const std::uint64_t n = pod<std::uint64_t>();
    const std::size_t padding = (kArrayAlignment - at_ % kArrayAlignment) % kArrayAlignment;
    need(padding, "an array's padding");
    for (std::size_t i = 0; i < padding; ++i)
      if (in_[at_ + i] != 0) throw std::runtime_error("an array's padding is not zero");
    at_ += padding;
    if (n > (in_.size() - at_) / elementSize)
      throw std::runtime_error("an array of " + std::to_string(n) + " elements runs past the end");
    const std::span<const std::uint8_t> bytes = in_.subspan(at_, n * elementSize);
    at_ += bytes.size();
    return bytes;
  }
  template <class E>
  E enumeration(std::uint8_t last, const char* what) {
    const auto v = pod<std::uint8_t>();
    if (v > last) throw std::runtime_error(std::string(what) + " " + std::to_string(v) + " is out of range");
    return static_cast<E>(v);
  }
  bool done() const { return at_ == in_.size(); }

 private:
  void need(std::size_t n, const char* what) {
    if (in_.size() - at_ < n) throw std::runtime_error(std::string("the data ends inside ") + what);
  }
  std::span<const std::uint8_t> in_;
  std::size_t at_ = 0;
};

// A flag, then the values (checked with the rest by validateScene).
void putVolume(Writer& w, const std::optional<Volume>& v) {
  static_assert(std::is_trivially_copyable_v<Volume>);
  w.pod(std::uint8_t(v.has_value()));
  if (v) w.pod(*v);
}

std::optional<Volume> getVolume(Reader& r) {
  if (r.enumeration<std::uint8_t>(1, "a volume flag") == 0) return std::nullopt;
  return r.pod<Volume>();
}

void put(Writer& w, const Material& m) {
  w.text(m.name);
  w.pod(m.baseColor);
  w.pod(m.opacity);
  w.pod(m.baseColorImage);
  w.pod(m.metallic);
  w.pod(m.roughness);
  w.pod(m.metallicRoughnessImage);
  w.pod(m.emission);
  w.pod(m.emissionStrength);
  w.pod(m.emissionImage);
  w.pod(m.transmission);
  w.pod(m.transmissionImage);
  w.pod(m.ior);
  w.pod(m.normalImage);
  w.pod(m.normalScale);
  w.pod(std::uint8_t(m.alphaMode));
  w.pod(m.alphaCutoff);
  w.pod(m.occlusionImage);
  w.pod(m.occlusionStrength);
  w.array(m.uvTransforms);
  putVolume(w, m.volume);
}

Material getMaterial(Reader& r) {
  Material m;
  m.name = r.text();
  m.baseColor = r.pod<Vec3>();
  m.opacity = r.pod<float>();
  m.baseColorImage = r.pod<int>();
  m.metallic = r.pod<float>();
  m.roughness = r.pod<float>();
  m.metallicRoughnessImage = r.pod<int>();
  m.emission = r.pod<Vec3>();
  m.emissionStrength = r.pod<float>();
  m.emissionImage = r.pod<int>();
  m.transmission = r.pod<float>();
  m.transmissionImage = r.pod<int>();
  m.ior = r.pod<float>();
  m.normalImage = r.pod<int>();
  m.normalScale = r.pod<float>();
  m.alphaMode = r.enumeration<AlphaMode>(std::uint8_t(AlphaMode::Count) - 1, "an alpha mode");
  m.alphaCutoff = r.pod<float>();
  m.occlusionImage = r.pod<int>();
  m.occlusionStrength = r.pod<float>();
  m.uvTransforms = r.array<Vec3>();
  m.volume = getVolume(r);
  return m;
}

void put(Writer& w, const Node& n) {
  w.text(n.name);
  w.pod(n.local);
  w.pod(std::uint8_t(n.trs.has_value()));
  if (n.trs) {
    w.pod(n.trs->translation);
    w.pod(n.trs->rotation);
    w.pod(n.trs->scale);
  }
  w.array(n.children);
  w.pod(n.mesh);
  w.pod(n.light);
  w.pod(n.camera);
}

Node getNode(Reader& r) {
  Node n;
  n.name = r.text();
  n.local = r.pod<Mat4>();
  if (r.enumeration<std::uint8_t>(1, "a pose flag")) {
    Animation::Pose p;
    p.translation = r.pod<Vec3>();
    p.rotation = r.pod<glm::quat>();
    p.scale = r.pod<Vec3>();
    n.trs = p;
  }
  n.children = r.array<int>();
  n.mesh = r.pod<int>();
  n.light = r.pod<int>();
  n.camera = r.pod<int>();
  return n;
}

}  // namespace

std::vector<std::uint8_t> encodeScene(const Scene& s) {
  std::vector<std::uint8_t> out;
  encodeScene(s, [&](std::span<const std::uint8_t> piece) { out.insert(out.end(), piece.begin(), piece.end()); });
  return out;
}

void encodeScene(const Scene& s, const ByteSink& sink) {
  Writer w(sink);
  w.pod(std::uint64_t(s.images.size()));
  for (const Image& i : s.images) {
    w.text(i.name);
    w.text(i.uri);
    w.pod(i.width);
    w.pod(i.height);
    w.pod(i.channels);
    w.array(i.pixels);
    w.pod(std::uint8_t(i.colorSpace));
  }
  w.pod(std::uint64_t(s.materials.size()));
  for (const Material& m : s.materials) put(w, m);
  w.pod(std::uint64_t(s.primitives.size()));
  for (const Primitive& p : s.primitives) {
    const ArrayViews a = p.arrays();
    w.array(a.positions);
    w.array(a.normals);
    w.array(a.uvs);
    w.array(a.colors);
    w.array(a.indices);
    w.pod(p.material);
    w.pod(std::uint8_t(p.animated));
    w.pod(std::uint8_t(p.primitive));
  }
  w.pod(std::uint64_t(s.meshes.size()));
  for (const Mesh& m : s.meshes) {
    w.text(m.name);
    w.array(m.primitives);
  }
  w.pod(std::uint64_t(s.lights.size()));
  for (const Light& l : s.lights) {
    w.text(l.name);
    w.pod(std::uint8_t(l.kind));
    w.pod(l.color);
    w.pod(l.intensity);
    w.pod(l.innerCone);
    w.pod(l.outerCone);
  }
  w.pod(std::uint64_t(s.cameras.size()));
  for (const Camera& c : s.cameras) {
    w.text(c.name);
    w.pod(c.yfov);
    w.pod(c.znear);
    w.pod(c.zfar);
    w.pod(c.apertureRadius);
    w.pod(c.focusDistance);
  }
  w.pod(std::uint64_t(s.nodes.size()));
  for (const Node& n : s.nodes) put(w, n);
  w.array(s.roots);
  w.pod(std::uint64_t(s.animations.size()));
  for (const AnimationClip& a : s.animations) {
    w.text(a.name);
    w.pod(std::uint8_t(a.looping));
    w.pod(std::uint64_t(a.channels.size()));
    for (const AnimationChannel& c : a.channels) {
      w.pod(c.node);
      w.pod(std::uint8_t(c.path));
      w.pod(std::uint8_t(c.interpolation));
      w.array(c.times);
      w.array(c.values);
    }
  }
  w.pod(s.background);
  putVolume(w, s.medium);
  w.pod(std::uint64_t(s.warnings.size()));
  for (const std::string& warning : s.warnings) w.text(warning);
  w.pod(std::uint64_t(s.skippedPrimitives));
  w.pod(s.metresPerUnit);
  w.finish();
}

Scene decodeScene(std::span<const std::uint8_t> bytes, const std::shared_ptr<const void>& keeper) {
  Reader r(bytes);
  Scene s;
  s.images.resize(r.count(37));
  for (Image& i : s.images) {
    i.name = r.text();
    i.uri = r.text();
    i.width = r.pod<std::uint32_t>();
    i.height = r.pod<std::uint32_t>();
    i.channels = r.pod<std::uint32_t>();
    i.pixels = r.array<std::uint8_t>();
    i.colorSpace = r.enumeration<ColorSpace>(std::uint8_t(ColorSpace::Linear), "a colour space");
  }
  s.materials.resize(r.count(81));
  for (Material& m : s.materials) m = getMaterial(r);
  s.primitives.resize(r.count(46));
  for (Primitive& p : s.primitives) {
    if (keeper) {
      p.held = HeldArrays{r.held<Vec3>(keeper), r.held<Vec3>(keeper), r.held<Vec2>(keeper), r.held<Vec4>(keeper),
                          r.held<std::uint32_t>(keeper)};
    } else {
      p.positions = r.array<Vec3>();
      p.normals = r.array<Vec3>();
      p.uvs = r.array<Vec2>();
      p.colors = r.array<Vec4>();
      p.indices = r.array<std::uint32_t>();
    }
    p.material = r.pod<int>();
    p.animated = r.enumeration<std::uint8_t>(1, "an animated flag") != 0;
    p.primitive =
        GeometryPrimitive(r.enumeration<std::uint8_t>(std::uint8_t(GeometryPrimitive::Count) - 1, "a primitive kind"));
  }
  s.meshes.resize(r.count(16));
  for (Mesh& m : s.meshes) {
    m.name = r.text();
    m.primitives = r.array<int>();
  }
  s.lights.resize(r.count(37));
  for (Light& l : s.lights) {
    l.name = r.text();
    l.kind = r.enumeration<LightKind>(std::uint8_t(LightKind::Directional), "a light kind");
    l.color = r.pod<Vec3>();
    l.intensity = r.pod<float>();
    l.innerCone = r.pod<float>();
    l.outerCone = r.pod<float>();
  }
  s.cameras.resize(r.count(28));
  for (Camera& c : s.cameras) {
    c.name = r.text();
    c.yfov = r.pod<float>();
    c.znear = r.pod<float>();
    c.zfar = r.pod<float>();
    c.apertureRadius = r.pod<float>();
    c.focusDistance = r.pod<float>();
  }
  s.nodes.resize(r.count(93));
  for (Node& n : s.nodes) n = getNode(r);
  s.roots = r.array<int>();
  s.animations.resize(r.count(17));
  for (AnimationClip& a : s.animations) {
    a.name = r.text();
    a.looping = r.enumeration<std::uint8_t>(1, "a looping flag") != 0;
    a.channels.resize(r.count(22));
    for (AnimationChannel& c : a.channels) {
      c.node = r.pod<int>();
      c.path = r.enumeration<Animation::Path>(std::uint8_t(Animation::Path::Scale), "an animation path");
      c.interpolation = r.enumeration<Animation::Interpolation>(std::uint8_t(Animation::Interpolation::CubicSpline),
                                                                "an interpolation");
      c.times = r.array<float>();
      c.values = r.array<Vec4>();
    }
  }
  s.background = r.pod<Vec3>();
  s.medium = getVolume(r);
  s.warnings.resize(r.count(8));
  for (std::string& warning : s.warnings) warning = r.text();
  s.skippedPrimitives = r.pod<std::uint64_t>();
  s.metresPerUnit = r.pod<float>();
  if (!(s.metresPerUnit > 0.0f && std::isfinite(s.metresPerUnit)))
    throw std::runtime_error("a scene unit of " + std::to_string(s.metresPerUnit) + " m: expected a length above 0");
  if (!r.done()) throw std::runtime_error("bytes follow the scene");
  validateScene(s);
  return s;
}

}  // namespace tsr::sg::parsed
