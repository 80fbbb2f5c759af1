#include "gltf/gltf_importer.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <spdlog/spdlog.h>
#include <glm/gtc/type_ptr.hpp>

#include "gltf/draco_primitive.hpp"
#include "gltf/gltf_accessors.hpp"
#include "gltf/gltf_loader.hpp"
#include "gltf/normal_generation.hpp"
#include "images/image_decoding.hpp"
#include "tsr/sg/coordinate_limit.hpp"

namespace tsr::sg::gltf {
namespace {

std::string str(std::size_t v) { return std::to_string(v); }
std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

class Converter {
 public:
  Converter(const LoadedFile& file, std::string source, const ImportOptions& options, parsed::Scene& out)
      : m_(file.model),
        dracoIndices_(file.dracoIndices),
        source_(std::move(source)),
        options_(options),
        out_(out),
        reader_(m_, source_, options) {}

  void run() {
    textureImages();
    images();
    materials();
    meshes();
    lights();
    cameras();
    nodes();
    roots();
    sceneMedium();
    placements();
    animations();
  }

 private:
  [[noreturn]] void fail(const std::string& reason) const { throw ImportError(source_, reason); }
  void warn(std::string w) {
    spdlog::debug("{}: {}", source_, w);
    out_.warnings.push_back(std::move(w));
  }

  // An index into one of the document's arrays, checked.
  int checked(int index, std::size_t size, const std::string& what, const std::string& kind) const {
    if (index < 0 || static_cast<std::size_t>(index) >= size)
      fail(what + " names " + kind + " " + std::to_string(index) + ", but there are " + str(size));
    return index;
  }

  float finite(double v, const std::string& what) const {
    const auto f = static_cast<float>(v);
    if (!std::isfinite(f)) fail(what + " is not finite");
    return f;
  }
  // A value that places something (a vertex, a node, a camera): finite and
  // within sg::kMaxCoordinate, beyond which no back-end can trace it.
  float coordinate(double v, const std::string& what) const {
    const float f = finite(v, what);
    if (!withinCoordinateLimit(f))
      fail(what + " " + number(v) + " is beyond " + number(kMaxCoordinate) +
           ", the largest coordinate Tessera renders");
    return f;
  }
  void checkCoordinates(const Mat4& m, const std::string& what) const {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) coordinate(m[c][r], what);
  }

  template <int N>
  glm::vec<N, float> vec(const std::vector<double>& v, const std::string& what) const {
    if (v.size() != N) fail(what + " must have " + std::to_string(N) + " numbers");
    glm::vec<N, float> out;
    for (int i = 0; i < N; ++i) out[i] = finite(v[static_cast<std::size_t>(i)], what);
    return out;
  }

  Vec3 position(const std::vector<double>& v, const std::string& what) const {
    if (v.size() != 3) fail(what + " must have 3 numbers");
    return {coordinate(v[0], what), coordinate(v[1], what), coordinate(v[2], what)};
  }

  void images() {
    for (std::size_t i = 0; i < m_.images.size(); ++i) {
      const tinygltf::Image& src = m_.images[i];
      const std::string what =
          "image " + str(i) + (src.uri.empty() || src.uri.rfind("data:", 0) == 0 ? "" : " ('" + src.uri + "')");
      std::vector<std::uint8_t> bytes;
      if (src.bufferView >= 0) {
        bytes = reader_.viewBytes(src.bufferView, what);
      } else {
        if (src.image.empty()) fail(what + ": file missing, unreadable or empty");
        bytes = src.image;
      }
      parsed::Image img = decodeImage(bytes, src.mimeType, options_.maxImagePixels, source_, what);
      img.name = src.name;
      if (src.bufferView < 0 && src.uri.rfind("data:", 0) != 0) img.uri = src.uri;
      out_.images.push_back(std::move(img));
    }
  }

  void textureImages() {
    for (std::size_t i = 0; i < m_.textures.size(); ++i) {
      const int source = m_.textures[i].source;
      if (source < 0) fail("texture " + str(i) + " has no image source (only PNG and JPEG images are supported)");
      textureImage_.push_back(checked(source, m_.images.size(), "texture " + str(i), "image"));
    }
    imageUse_.assign(m_.images.size(), 0);
  }

  // The image behind a texture slot, remembering whether it holds colour.
  int texture(int index, const std::string& what, bool color) {
    if (index < 0) return parsed::kNone;
    const int image = textureImage_[static_cast<std::size_t>(checked(index, m_.textures.size(), what, "texture"))];
    auto& use = imageUse_[static_cast<std::size_t>(image)];
    const int bit = color ? 1 : 2;
    if (use && !(use & bit)) warn("image " + std::to_string(image) + " is used both as colour and as data");
    use |= bit;
    out_.images[static_cast<std::size_t>(image)].colorSpace = (use & 1) ? ColorSpace::SRGB : ColorSpace::Linear;
    return image;
  }

  double extensionNumber(const tinygltf::ExtensionMap& ext, const char* name, const char* key, double fallback) const {
    auto it = ext.find(name);
    if (it == ext.end() || !it->second.Has(key)) return fallback;
    return it->second.Get(key).GetNumberAsDouble();
  }
  int extensionTexture(const tinygltf::ExtensionMap& ext, const char* name, const char* key) const {
    auto it = ext.find(name);
    if (it == ext.end() || !it->second.Has(key) || !it->second.Get(key).Has("index")) return -1;
    return it->second.Get(key).Get("index").GetNumberAsInt();
  }

  void materials() {
    for (std::size_t i = 0; i < m_.materials.size(); ++i) {
      const tinygltf::Material& src = m_.materials[i];
      const std::string what = "material " + str(i);
      const auto& pbr = src.pbrMetallicRoughness;
      parsed::Material mat;
      mat.name = src.name;
      const Vec4 base = vec<4>(pbr.baseColorFactor, what + " baseColorFactor");
      mat.baseColor = Vec3(base);
      mat.opacity = src.alphaMode == "OPAQUE" ? 1.0f : base.a;
      if (src.alphaMode == "MASK") {
        mat.alphaMode = AlphaMode::Mask;
      } else if (src.alphaMode == "BLEND") {
        mat.alphaMode = AlphaMode::Blend;
      } else if (src.alphaMode != "OPAQUE") {
        fail(what + " alphaMode '" + src.alphaMode + "' is none of OPAQUE, MASK, BLEND");
      }
      mat.alphaCutoff = finite(src.alphaCutoff, what + " alphaCutoff");
      mat.baseColorImage = texture(pbr.baseColorTexture.index, what + " baseColorTexture", true);
      mat.metallic = finite(pbr.metallicFactor, what + " metallicFactor");
      mat.roughness = finite(pbr.roughnessFactor, what + " roughnessFactor");
      mat.metallicRoughnessImage =
          texture(pbr.metallicRoughnessTexture.index, what + " metallicRoughnessTexture", false);
      mat.emission = vec<3>(src.emissiveFactor, what + " emissiveFactor");
      mat.emissionImage = texture(src.emissiveTexture.index, what + " emissiveTexture", true);
      mat.normalImage = texture(src.normalTexture.index, what + " normalTexture", false);
      mat.normalScale = finite(src.normalTexture.scale, what + " normalTexture scale");
      mat.emissionStrength =
          finite(extensionNumber(src.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1.0),
                 what + " emissiveStrength");
      mat.transmission =
          finite(extensionNumber(src.extensions, "KHR_materials_transmission", "transmissionFactor", 0.0),
                 what + " transmissionFactor");
      mat.transmissionImage =
          texture(extensionTexture(src.extensions, "KHR_materials_transmission", "transmissionTexture"),
                  what + " transmissionTexture", false);
      mat.ior = finite(extensionNumber(src.extensions, "KHR_materials_ior", "ior", 1.5), what + " ior");
      mat.occlusionImage = texture(src.occlusionTexture.index, what + " occlusionTexture", false);
      mat.occlusionStrength = finite(src.occlusionTexture.strength, what + " occlusionTexture strength");
      uvTransforms(src, what, mat);
      mat.volume = materialVolume(src.extensions, what);
      out_.materials.push_back(mat);
    }
  }

  // KHR_texture_transform on each texture slot, as two rows of an affine
  // map per slot (offset x rotation x scale); none at all keeps the list empty.
  void uvTransforms(const tinygltf::Material& src, const std::string& what, parsed::Material& mat) {
    const tinygltf::Value* transmission = nullptr;
    if (auto it = src.extensions.find("KHR_materials_transmission"); it != src.extensions.end())
      if (it->second.Has("transmissionTexture")) transmission = &it->second.Get("transmissionTexture");
    const std::pair<TextureSlot, const tinygltf::ExtensionMap*> slots[] = {
        {TextureSlot::BaseColor, &src.pbrMetallicRoughness.baseColorTexture.extensions},
        {TextureSlot::MetallicRoughness, &src.pbrMetallicRoughness.metallicRoughnessTexture.extensions},
        {TextureSlot::Emission, &src.emissiveTexture.extensions},
        {TextureSlot::Normal, &src.normalTexture.extensions},
        {TextureSlot::Occlusion, &src.occlusionTexture.extensions}};
    auto place = [&](TextureSlot slot, const tinygltf::Value& t) {
      if (mat.uvTransforms.empty()) {
        for (std::size_t i = 0; i < SurfaceMaterial::kUvTransformRows; i += 2)
          mat.uvTransforms.insert(mat.uvTransforms.end(), {Vec3(1, 0, 0), Vec3(0, 1, 0)});
      }
      const std::string at = what + " KHR_texture_transform";
      Vec2 offset(0.0f), scale(1.0f);
      float rotation = 0.0f;
      for (int k = 0; k < 2; ++k) {
        if (t.Has("offset")) offset[k] = finite(t.Get("offset").Get(k).GetNumberAsDouble(), at + " offset");
        if (t.Has("scale")) scale[k] = finite(t.Get("scale").Get(k).GetNumberAsDouble(), at + " scale");
      }
      if (t.Has("rotation")) rotation = finite(t.Get("rotation").GetNumberAsDouble(), at + " rotation");
      if (t.Has("texCoord") && t.Get("texCoord").GetNumberAsInt() != 0)
        warn(at + " names texCoord " + str(t.Get("texCoord").GetNumberAsInt()) + ": the first uv set is used");
      const float c = std::cos(rotation), s = std::sin(rotation);
      const auto i = 2 * static_cast<std::size_t>(slot);
      mat.uvTransforms[i] = Vec3(c * scale.x, s * scale.y, offset.x);
      mat.uvTransforms[i + 1] = Vec3(-s * scale.x, c * scale.y, offset.y);
    };
    for (const auto& [slot, ext] : slots)
      if (auto it = ext->find("KHR_texture_transform"); it != ext->end()) place(slot, it->second);
    if (transmission && transmission->Has("extensions") && transmission->Get("extensions").Has("KHR_texture_transform"))
      place(TextureSlot::Transmission, transmission->Get("extensions").Get("KHR_texture_transform"));
  }

  // A coefficient triple of a volume extension: finite, not negative.
  Vec3 coefficients(const tinygltf::Value& v, const std::string& what) const {
    if (!v.IsArray() || v.ArrayLen() != 3) fail(what + " must have 3 numbers");
    Vec3 out;
    for (int i = 0; i < 3; ++i) {
      out[i] = finite(v.Get(i).GetNumberAsDouble(), what);
      if (out[i] < 0.0f) fail(what + " must not be negative");
    }
    return out;
  }

  // TSR_materials_volume / TSR_scene_medium over `into`; textures only in
  // a material's (the scene's medium has no mesh to stretch them over).
  void tesseraVolume(const tinygltf::Value& ext, const std::string& what, parsed::Volume& into, bool textures) {
    const char* keys[] = {"absorptionTexture", "scatteringTexture", "emissionTexture"};
    int* images[] = {&into.absorptionImage, &into.scatteringImage, &into.emissionImage};
    for (int k = 0; k < 3; ++k) {
      if (!ext.Has(keys[k])) continue;
      if (!textures) fail(what + " " + keys[k] + ": a scene-wide medium cannot be textured");
      const tinygltf::Value& info = ext.Get(keys[k]);
      if (!info.Has("index")) fail(what + " " + keys[k] + " has no index");
      // Densities, not colours: read as linear values.
      *images[k] = texture(info.Get("index").GetNumberAsInt(), what + " " + keys[k], false);
    }
    if (ext.Has("textureSlices")) {
      if (!textures) fail(what + " textureSlices: a scene-wide medium cannot be textured");
      const double n = ext.Get("textureSlices").GetNumberAsDouble();
      if (!(n >= 1.0 && n <= double(parsed::kMaxTextureSlices) && n == std::floor(n)))
        fail(what + " textureSlices must be a whole number from 1 to " + str(parsed::kMaxTextureSlices));
      into.textureSlices = static_cast<std::uint32_t>(n);
    }
    for (int k = 0; k < 3; ++k) {
      if (*images[k] == parsed::kNone) continue;
      const std::uint32_t rows = out_.images[static_cast<std::size_t>(*images[k])].height;
      if (rows % into.textureSlices != 0)
        fail(what + " " + keys[k] + ": image " + str(*images[k]) + " is " + str(rows) + " rows high, not " +
             str(into.textureSlices) + " slices of equal height");
    }
    if (ext.Has("emission")) into.emission = coefficients(ext.Get("emission"), what + " emission");
    if (ext.Has("absorption")) into.absorption = coefficients(ext.Get("absorption"), what + " absorption");
    if (ext.Has("scattering")) into.scattering = coefficients(ext.Get("scattering"), what + " scattering");
    if (ext.Has("phaseG")) {
      into.phaseG = finite(ext.Get("phaseG").GetNumberAsDouble(), what + " phaseG");
      if (!(into.phaseG > -1.0f && into.phaseG < 1.0f)) fail(what + " phaseG must lie strictly between -1 and 1");
    }
  }

  // KHR_materials_volume's attenuation (Beer's law: colour c left after
  // distance d, so sigma_a = -ln(c) / d), then Tessera's own extension
  // for scattering, emission and the phase function.
  std::optional<parsed::Volume> materialVolume(const tinygltf::ExtensionMap& ext, const std::string& what) {
    auto khr = ext.find("KHR_materials_volume");
    auto tsr = ext.find("TSR_materials_volume");
    if (khr == ext.end() && tsr == ext.end()) return std::nullopt;
    parsed::Volume v;
    if (khr != ext.end() && khr->second.Has("attenuationDistance")) {
      const std::string at = what + " KHR_materials_volume";
      const float distance = finite(khr->second.Get("attenuationDistance").GetNumberAsDouble(), at);
      if (!(distance > 0.0f)) fail(at + " attenuationDistance must be positive");
      Vec3 colour(1.0f);
      if (khr->second.Has("attenuationColor")) colour = coefficients(khr->second.Get("attenuationColor"), at);
      for (int c = 0; c < 3; ++c) {
        if (colour[c] > 1.0f) fail(at + " attenuationColor must lie in [0, 1]");
        // Colour 0 means nothing gets through: an opaque absorber, kept finite.
        v.absorption[c] = -std::log(std::max(colour[c], 1e-6f)) / distance;
      }
    }
    if (tsr != ext.end()) tesseraVolume(tsr->second, what + " TSR_materials_volume", v, true);
    return v;
  }

  void sceneMedium() {
    if (m_.scenes.empty()) return;
    const auto index = static_cast<std::size_t>(m_.defaultScene < 0 ? 0 : m_.defaultScene);
    const auto& ext = m_.scenes[index].extensions;
    auto it = ext.find("TSR_scene_medium");
    if (it == ext.end()) return;
    parsed::Volume medium;
    tesseraVolume(it->second, "scene " + str(index) + " TSR_scene_medium", medium, false);
    out_.medium = medium;
  }

  template <int N>
  std::vector<glm::vec<N, float>> attribute(int accessor, bool normalizedInts, const std::string& what) {
    const std::vector<float> f = reader_.floats(accessor, N, normalizedInts, what);
    std::vector<glm::vec<N, float>> out(f.size() / N);
    for (std::size_t i = 0; i < out.size(); ++i)
      for (int c = 0; c < N; ++c) out[i][c] = f[i * N + static_cast<std::size_t>(c)];
    return out;
  }

  // Every mode becomes a list: triangle strips and fans a triangle list,
  // line strips and loops a list of segments; points stay points.
  void primitiveList(int mode, parsed::Primitive& p, const std::string& what) {
    std::vector<std::uint32_t>& idx = p.indices;
    auto whole = [&](std::size_t per, const char* of) {
      if (idx.size() % per) {
        warn(what + ": " + str(idx.size()) + " indices is not a multiple of " + str(per) + " (" + of +
             "); the rest is dropped");
        idx.resize(idx.size() - idx.size() % per);
      }
    };
    switch (mode) {
      case TINYGLTF_MODE_TRIANGLES:
        whole(3, "triangles");
        return;
      case TINYGLTF_MODE_TRIANGLE_STRIP: {
        std::vector<std::uint32_t> list;
        for (std::size_t i = 0; i + 2 < idx.size(); ++i) {
          // Every other triangle flips so all keep the strip's winding.
          if (i % 2 == 0)
            list.insert(list.end(), {idx[i], idx[i + 1], idx[i + 2]});
          else
            list.insert(list.end(), {idx[i + 1], idx[i], idx[i + 2]});
        }
        idx = std::move(list);
        return;
      }
      case TINYGLTF_MODE_TRIANGLE_FAN: {
        std::vector<std::uint32_t> list;
        for (std::size_t i = 1; i + 1 < idx.size(); ++i) list.insert(list.end(), {idx[0], idx[i], idx[i + 1]});
        idx = std::move(list);
        return;
      }
      case TINYGLTF_MODE_POINTS:
        p.primitive = GeometryPrimitive::Points;
        return;
      case TINYGLTF_MODE_LINE:
        p.primitive = GeometryPrimitive::Lines;
        whole(2, "line segments");
        return;
      case TINYGLTF_MODE_LINE_LOOP:
      case TINYGLTF_MODE_LINE_STRIP: {
        p.primitive = GeometryPrimitive::Lines;
        std::vector<std::uint32_t> list;
        for (std::size_t i = 0; i + 1 < idx.size(); ++i) list.insert(list.end(), {idx[i], idx[i + 1]});
        // A loop closes back to its first vertex (one of a single vertex draws nothing).
        if (mode == TINYGLTF_MODE_LINE_LOOP && idx.size() > 2) list.insert(list.end(), {idx.back(), idx.front()});
        idx = std::move(list);
        return;
      }
      default:
        fail(what + " has unknown mode " + std::to_string(mode));
    }
  }

  // The scene graph holds no value beyond kMaxCoordinate in any vertex
  // array: said here as an import error, not later as the scene's.
  template <class Vec>
  void withinLimit(const std::vector<Vec>& values, const std::string& what) const {
    for (std::size_t v = 0; v < values.size(); ++v)
      for (int c = 0; c < Vec::length(); ++c)
        if (!withinCoordinateLimit(values[v][c]))
          fail(what + " element " + str(v) + " is " + number(values[v][c]) + ", beyond +-" + number(kMaxCoordinate));
  }

  // A primitive's vertices and indices from its accessors.
  void readAccessors(const tinygltf::Primitive& src, const std::string& what, parsed::Primitive& p) {
    auto attr = [&](const char* name) {
      auto it = src.attributes.find(name);
      return it == src.attributes.end() ? -1 : it->second;
    };
    if (attr("POSITION") < 0) fail(what + " has no POSITION attribute");
    p.positions = attribute<3>(attr("POSITION"), false, what + " POSITION");
    const std::size_t n = p.positions.size();
    auto sameCount = [&](std::size_t count, const char* name) {
      if (count != n) fail(what + " " + name + " has " + str(count) + " elements but POSITION has " + str(n));
    };
    if (attr("NORMAL") >= 0) {
      p.normals = attribute<3>(attr("NORMAL"), false, what + " NORMAL");
      sameCount(p.normals.size(), "NORMAL");
    }
    if (attr("TEXCOORD_0") >= 0) {
      p.uvs = attribute<2>(attr("TEXCOORD_0"), true, what + " TEXCOORD_0");
      sameCount(p.uvs.size(), "TEXCOORD_0");
    }
    if (const int c = attr("COLOR_0"); c >= 0) {
      const std::size_t comps = c < static_cast<int>(m_.accessors.size()) &&
                                        m_.accessors[static_cast<std::size_t>(c)].type == TINYGLTF_TYPE_VEC3
                                    ? 3
                                    : 4;
      if (comps == 3) {
        for (const Vec3& rgb : attribute<3>(c, true, what + " COLOR_0")) p.colors.emplace_back(rgb, 1.0f);
      } else {
        p.colors = attribute<4>(c, true, what + " COLOR_0");
      }
      sameCount(p.colors.size(), "COLOR_0");
    }
    if (src.indices >= 0) {
      p.indices = reader_.indices(src.indices, what + " indices");
    } else {
      p.indices.resize(n);
      for (std::size_t i = 0; i < n; ++i) p.indices[i] = static_cast<std::uint32_t>(i);
    }
  }

  void meshes() {
    for (std::size_t mi = 0; mi < m_.meshes.size(); ++mi) {
      parsed::Mesh mesh{m_.meshes[mi].name, {}};
      const auto& prims = m_.meshes[mi].primitives;
      for (std::size_t pi = 0; pi < prims.size(); ++pi) {
        const tinygltf::Primitive& src = prims[pi];
        const std::string what = "mesh " + str(mi) + " primitive " + str(pi);
        parsed::Primitive p;
        if (src.material >= 0) p.material = checked(src.material, m_.materials.size(), what, "material");
        const auto draco = dracoIndices_.find({mi, pi});
        if (draco != dracoIndices_.end())
          decodeDracoPrimitive(m_, src, draco->second, options_.maxAccessorElements, dracoElementsLeft_, source_, what,
                               p);
        else
          readAccessors(src, what, p);
        const std::size_t n = p.positions.size();
        for (std::size_t v = 0; v < n; ++v)
          for (int c = 0; c < 3; ++c) coordinate(p.positions[v][c], what + " POSITION " + str(v) + " coordinate");
        withinLimit(p.normals, what + " NORMAL");
        withinLimit(p.uvs, what + " TEXCOORD_0");
        withinLimit(p.colors, what + " COLOR_0");
        for (std::size_t i = 0; i < p.indices.size(); ++i)
          if (p.indices[i] >= n)
            fail(what + " index " + str(i) + " is " + std::to_string(p.indices[i]) + ", but there are only " + str(n) +
                 " vertices");
        // A Draco stream is a triangle list whatever the mode says.
        primitiveList(draco != dracoIndices_.end() ? TINYGLTF_MODE_TRIANGLES : src.mode, p, what);
        if (p.indices.empty()) {
          warn(what + " has nothing to draw; skipped");
          ++out_.skippedPrimitives;
          continue;
        }
        // Lines and points have no surface: they are drawn unlit, without normals.
        if (p.normals.empty() && options_.smoothNormals && p.primitive == GeometryPrimitive::Triangles)
          generateSmoothNormals(p);
        out_.primitives.push_back(std::move(p));
        mesh.primitives.push_back(static_cast<int>(out_.primitives.size()) - 1);
      }
      out_.meshes.push_back(std::move(mesh));
    }
  }

  void lights() {
    for (std::size_t i = 0; i < m_.lights.size(); ++i) {
      const tinygltf::Light& src = m_.lights[i];
      const std::string what = "light " + str(i);
      parsed::Light l;
      l.name = src.name;
      if (src.type == "point")
        l.kind = LightKind::Point;
      else if (src.type == "spot")
        l.kind = LightKind::Spot;
      else if (src.type == "directional")
        l.kind = LightKind::Directional;
      else
        fail(what + " has unknown type '" + src.type + "'");
      if (!src.color.empty()) l.color = vec<3>(src.color, what + " color");
      l.intensity = finite(src.intensity, what + " intensity");
      // range is checked, then dropped: light falls off with the square of
      // the distance and ends nowhere, as in Blender (glTF allows that).
      if (l.intensity < 0.0f || finite(src.range, what + " range") < 0.0f)
        fail(what + " has a negative intensity or range");
      if (l.kind == LightKind::Spot) {
        l.innerCone = finite(src.spot.innerConeAngle, what + " innerConeAngle");
        l.outerCone = finite(src.spot.outerConeAngle, what + " outerConeAngle");
        if (l.innerCone < 0.0f || l.outerCone <= l.innerCone || l.outerCone > 1.5707964f)
          fail(what + " needs 0 <= innerConeAngle < outerConeAngle <= pi/2");
      }
      out_.lights.push_back(l);
    }
  }

  void cameras() {
    for (std::size_t i = 0; i < m_.cameras.size(); ++i) {
      const tinygltf::Camera& src = m_.cameras[i];
      const std::string what = "camera " + str(i);
      if (src.type != "perspective") {
        warn(what + " is " + src.type + "; only perspective cameras are imported");
        cameraIndex_.push_back(parsed::kNone);
        continue;
      }
      parsed::Camera c;
      c.name = src.name;
      c.yfov = finite(src.perspective.yfov, what + " yfov");
      c.znear = finite(src.perspective.znear, what + " znear");
      // glTF's zfar of 0 (absent) means an infinite projection.
      c.zfar = src.perspective.zfar > 0 ? finite(src.perspective.zfar, what + " zfar") : 1.0e30f;
      if (c.yfov <= 0.0f || c.yfov >= 3.1415926f || c.znear <= 0.0f || c.zfar <= c.znear)
        fail(what + " needs 0 < yfov < pi and 0 < znear < zfar");
      if (auto lens = src.extensions.find("TSR_camera_lens"); lens != src.extensions.end()) {
        const tinygltf::Value& v = lens->second;
        if (v.Has("apertureRadius"))
          c.apertureRadius = finite(v.Get("apertureRadius").GetNumberAsDouble(), what + " apertureRadius");
        if (v.Has("focusDistance"))
          c.focusDistance = finite(v.Get("focusDistance").GetNumberAsDouble(), what + " focusDistance");
        if (!(c.apertureRadius >= 0.0f) || !(c.focusDistance > 0.0f))
          fail(what + " TSR_camera_lens needs apertureRadius >= 0 and focusDistance > 0");
      }
      out_.cameras.push_back(c);
      cameraIndex_.push_back(static_cast<int>(out_.cameras.size()) - 1);
    }
  }

  void nodes() {
    for (std::size_t i = 0; i < m_.nodes.size(); ++i) {
      const tinygltf::Node& src = m_.nodes[i];
      const std::string what = "node " + str(i);
      parsed::Node node;
      node.name = src.name;
      node.children = src.children;  // checked by checkNodeGraph
      if (!src.matrix.empty()) {
        if (!src.translation.empty() || !src.rotation.empty() || !src.scale.empty())
          fail(what + " has both a matrix and translation/rotation/scale");
        if (src.matrix.size() != 16) fail(what + " matrix must have 16 numbers");
        float m[16];
        for (std::size_t k = 0; k < 16; ++k) m[k] = coordinate(src.matrix[k], what + " matrix");
        node.local = glm::make_mat4(m);
      } else {
        Animation::Pose pose;
        if (!src.translation.empty()) pose.translation = position(src.translation, what + " translation");
        if (!src.scale.empty()) pose.scale = position(src.scale, what + " scale");
        if (!src.rotation.empty()) {
          const Vec4 q = vec<4>(src.rotation, what + " rotation");
          const float len = glm::length(q);
          if (!(len > 1e-6f) || !std::isfinite(len)) fail(what + " rotation is not a unit quaternion");
          pose.rotation = glm::quat(q.w / len, q.x / len, q.y / len, q.z / len);
        }
        node.trs = pose;
        node.local = pose.matrix();
      }
      if (src.mesh >= 0) node.mesh = checked(src.mesh, m_.meshes.size(), what, "mesh");
      if (src.camera >= 0)
        node.camera = cameraIndex_[static_cast<std::size_t>(checked(src.camera, m_.cameras.size(), what, "camera"))];
      if (auto it = src.extensions.find("KHR_lights_punctual"); it != src.extensions.end() && it->second.Has("light"))
        node.light = checked(it->second.Get("light").GetNumberAsInt(), m_.lights.size(), what, "light");
      if (src.skin >= 0) warn(what + ": skins are not supported; the mesh is imported in its bind pose");
      out_.nodes.push_back(std::move(node));
    }
  }

  void roots() {
    std::vector<char> hasParent(m_.nodes.size(), 0);
    for (const auto& n : m_.nodes)
      for (int c : n.children) hasParent[static_cast<std::size_t>(c)] = 1;
    if (m_.scenes.empty()) {
      for (std::size_t i = 0; i < m_.nodes.size(); ++i)
        if (!hasParent[i]) out_.roots.push_back(static_cast<int>(i));
      return;
    }
    const int sceneIndex =
        m_.defaultScene < 0 ? 0 : checked(m_.defaultScene, m_.scenes.size(), "the document", "scene");
    std::vector<char> listed(m_.nodes.size(), 0);
    for (int r : m_.scenes[static_cast<std::size_t>(sceneIndex)].nodes) {
      const std::string what = "scene " + std::to_string(sceneIndex);
      const auto k = static_cast<std::size_t>(checked(r, m_.nodes.size(), what, "node"));
      if (hasParent[k]) fail(what + " lists node " + std::to_string(r) + ", which is a child of another node");
      if (listed[k]) fail(what + " lists node " + std::to_string(r) + " twice");
      listed[k] = 1;
      out_.roots.push_back(r);
    }
  }

  // Nodes compose their matrices: check where each one ends up in the world
  // (cameras above all: their position is every primary ray's origin).
  void placements() {
    std::vector<std::pair<int, Mat4>> stack;
    for (int r : out_.roots) stack.emplace_back(r, Mat4(1.0f));
    while (!stack.empty()) {
      auto [index, parent] = stack.back();
      stack.pop_back();
      const parsed::Node& n = out_.nodes[static_cast<std::size_t>(index)];
      const Mat4 world = parent * n.local;
      const bool camera = n.camera != parsed::kNone;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
          if (!withinCoordinateLimit(world[c][r]))
            fail("node " + str(static_cast<std::size_t>(index)) +
                 (camera && c == 3 ? " places its camera at " : " has world transform entry ") + number(world[c][r]) +
                 ", beyond " + number(kMaxCoordinate) +
                 ", the largest coordinate Tessera renders (the node hierarchy composes to it)");
      for (int child : n.children) stack.emplace_back(child, world);
    }
  }

  void animations() {
    for (std::size_t ai = 0; ai < m_.animations.size(); ++ai) {
      const tinygltf::Animation& src = m_.animations[ai];
      parsed::AnimationClip clip{src.name, false, {}};
      Animation check;  // applies Animation's own key checks before anything is built
      for (std::size_t ci = 0; ci < src.channels.size(); ++ci) {
        const tinygltf::AnimationChannel& ch = src.channels[ci];
        const std::string what = "animation " + str(ai) + " channel " + str(ci);
        parsed::AnimationChannel out;
        out.node = checked(ch.target_node, m_.nodes.size(), what, "node");
        if (ch.target_path == "translation")
          out.path = Animation::Path::Translation;
        else if (ch.target_path == "rotation")
          out.path = Animation::Path::Rotation;
        else if (ch.target_path == "scale")
          out.path = Animation::Path::Scale;
        else if (ch.target_path == "weights") {
          warn(what + ": morph target weights are not supported; channel skipped");
          continue;
        } else
          fail(what + " has unknown target path '" + ch.target_path + "'");
        if (!out_.nodes[static_cast<std::size_t>(out.node)].trs)
          fail(what + " animates node " + std::to_string(out.node) + ", which has a matrix instead of TRS");
        const auto& sampler =
            src.samplers[static_cast<std::size_t>(checked(ch.sampler, src.samplers.size(), what, "sampler"))];
        if (sampler.interpolation == "LINEAR" || sampler.interpolation.empty())
          out.interpolation = Animation::Interpolation::Linear;
        else if (sampler.interpolation == "STEP")
          out.interpolation = Animation::Interpolation::Step;
        else if (sampler.interpolation == "CUBICSPLINE")
          out.interpolation = Animation::Interpolation::CubicSpline;
        else
          fail(what + " has unknown interpolation '" + sampler.interpolation + "'");
        out.times = reader_.floats(sampler.input, 1, false, what + " input");
        const int comps = out.path == Animation::Path::Rotation ? 4 : 3;
        const std::vector<float> v = reader_.floats(sampler.output, comps, true, what + " output");
        if (out.path != Animation::Path::Rotation)
          for (const float x : v) coordinate(x, what + " output value");
        for (std::size_t k = 0; k < v.size(); k += static_cast<std::size_t>(comps))
          out.values.emplace_back(v[k], v[k + 1], v[k + 2], comps == 4 ? v[k + 3] : 0.0f);
        try {
          check.addChannel({0, out.path, out.interpolation, out.times, out.values});
        } catch (const std::invalid_argument& e) {
          fail(what + ": " + e.what());
        }
        clip.channels.push_back(std::move(out));
      }
      out_.animations.push_back(std::move(clip));
    }
  }

  const tinygltf::Model& m_;
  const DracoIndices& dracoIndices_;
  std::string source_;
  const ImportOptions& options_;
  std::uint64_t dracoElementsLeft_ = options_.maxAccessorElements;  // what Draco streams may still hold
  parsed::Scene& out_;
  AccessorReader reader_;
  std::vector<int> textureImage_;
  std::vector<int> imageUse_;
  std::vector<int> cameraIndex_;
};

}  // namespace

namespace {
parsed::Scene converted(LoadedFile file, const std::string& source, const ImportOptions& options) {
  parsed::Scene scene;
  scene.warnings = std::move(file.warnings);
  scene.readOtherFiles = file.readOtherFiles;
  Converter(file, source, options, scene).run();
  return scene;
}
}  // namespace

parsed::Scene parseFile(const std::string& path, const ImportOptions& options) {
  return converted(loadFile(path, options), path, options);
}

parsed::Scene parseBytes(std::span<const unsigned char> bytes, const std::string& source, const std::string& baseDir,
                         const ImportOptions& options) {
  return converted(loadBytes(bytes, source, baseDir, options), source, options);
}

}  // namespace tsr::sg::gltf
