#include "test_scenes.hpp"

#include "tsr/embree/sampling.hpp"

#include <cmath>
#include <cstring>
#include <fstream>

namespace tsr::embree::test {

std::shared_ptr<Device> sharedDevice() {
  static std::shared_ptr<Device> device = std::make_shared<Device>();
  return device;
}

MeshData uvSphere(const glm::vec3& c, float r, int tris, bool normals) {
  std::vector<glm::vec3> positions, normalsOut;
  std::vector<std::uint32_t> indices;
  int rings = std::max(4, int(std::sqrt(float(tris) / 4.0f)));
  int segs = 2 * rings;
  for (int i = 0; i <= rings; ++i) {
    float th = kPi * float(i) / float(rings);
    for (int j = 0; j < segs; ++j) {
      float ph = 2.0f * kPi * float(j) / float(segs);
      glm::vec3 n(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
      positions.push_back(c + r * n);
      if (normals) normalsOut.push_back(n);
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segs; ++j) {
      std::uint32_t a = i * segs + j, b = i * segs + (j + 1) % segs, cc = a + segs, d = b + segs;
      if (i > 0) indices.insert(indices.end(), {a, b, d});
      if (i < rings - 1) indices.insert(indices.end(), {a, d, cc});
    }
  }
  MeshData m;
  m.positions = std::move(positions);
  m.normals = std::move(normalsOut);
  m.indices = std::move(indices);
  return m;
}

MeshData quad(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3) {
  MeshData m;
  m.positions = {p0, p1, p2, p3};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

void floorUnderLamp(Scene& scene) {
  Material grey;
  grey.baseColor = glm::vec3(0.5f);
  scene.addInstance(scene.addMesh(quad({-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5})), scene.addMaterial(grey),
                    glm::mat4(1.0f));
  Material lamp;
  lamp.baseColor = glm::vec3(0.0f);
  lamp.emission = glm::vec3(20.0f);
  scene.addInstance(scene.addMesh(quad({-1, 5, -1}, {1, 5, -1}, {1, 5, 1}, {-1, 5, 1})), scene.addMaterial(lamp),
                    glm::mat4(1.0f));
}

MeshData box(const glm::vec3& lo, const glm::vec3& hi) {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
  for (int i = 0; i < 8; ++i)
    positions.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  const std::uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) indices.insert(indices.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
  MeshData m;
  m.positions = std::move(positions);
  m.indices = std::move(indices);
  return m;
}

glm::vec3 furnaceMean(Scene& scene, const Medium& medium) {
  Material boundary;
  boundary.type = MaterialType::Interface;
  boundary.interior = medium;
  scene.addInstance(scene.addMesh(uvSphere({0, 0, 0}, 1.0f, 2000, false)), scene.addMaterial(boundary),
                    glm::mat4(1.0f));
  scene.setEnvironment(Environment::constant(glm::vec3(0.5f)));
  RenderSettings s;
  s.maxDepth = 1000;
  s.samplesPerPass = 16;
  Renderer renderer(s);
  Camera camera = Camera::lookAt({0, 0, 3.5f}, {0, 0, 0}, {0, 1, 0}, glm::radians(30.0f), 1.0f);
  FrameBuffer fb(24, 24);
  render(renderer, scene, camera, Region::full(24, 24), fb, 16);
  return meanColour(fb);
}

Camera cornellBox(Scene& scene, int sphereTris, float aspect) {
  struct Q {
    int colour;
    glm::vec3 v[4];
  };
  const Q quads[] = {
      {0, {{552.8f, 0, 0}, {0, 0, 0}, {0, 0, 559.2f}, {549.6f, 0, 559.2f}}},
      {0, {{556, 548.8f, 0}, {556, 548.8f, 559.2f}, {0, 548.8f, 559.2f}, {0, 548.8f, 0}}},
      {0, {{549.6f, 0, 559.2f}, {0, 0, 559.2f}, {0, 548.8f, 559.2f}, {556, 548.8f, 559.2f}}},
      {2, {{0, 0, 559.2f}, {0, 0, 0}, {0, 548.8f, 0}, {0, 548.8f, 559.2f}}},
      {1, {{552.8f, 0, 0}, {549.6f, 0, 559.2f}, {556, 548.8f, 559.2f}, {556, 548.8f, 0}}},
      {0, {{130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}}},
      {0, {{290, 0, 114}, {290, 165, 114}, {240, 165, 272}, {240, 0, 272}}},
      {0, {{130, 0, 65}, {130, 165, 65}, {290, 165, 114}, {290, 0, 114}}},
      {0, {{82, 0, 225}, {82, 165, 225}, {130, 165, 65}, {130, 0, 65}}},
      {0, {{240, 0, 272}, {240, 165, 272}, {82, 165, 225}, {82, 0, 225}}},
      {0, {{423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}}},
      {0, {{423, 0, 247}, {423, 330, 247}, {472, 330, 406}, {472, 0, 406}}},
      {0, {{472, 0, 406}, {472, 330, 406}, {314, 330, 456}, {314, 0, 456}}},
      {0, {{314, 0, 456}, {314, 330, 456}, {265, 330, 296}, {265, 0, 296}}},
      {0, {{265, 0, 296}, {265, 330, 296}, {423, 330, 247}, {423, 0, 247}}},
  };
  const glm::vec3 colours[] = {{1, 1, 1}, {1, 0, 0}, {0, 1, 0}};
  std::vector<glm::vec3> positions[3];
  std::vector<std::uint32_t> indices[3];
  for (const Q& q : quads) {
    auto base = std::uint32_t(positions[q.colour].size());
    positions[q.colour].insert(positions[q.colour].end(), q.v, q.v + 4);
    indices[q.colour].insert(indices[q.colour].end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
  for (int c = 0; c < 3; ++c) {
    Material m;
    m.baseColor = colours[c];
    MeshData group;
    group.positions = std::move(positions[c]);
    group.indices = std::move(indices[c]);
    scene.addInstance(scene.addMesh(std::move(group)), scene.addMaterial(m), glm::mat4(1.0f));
  }
  if (sphereTris > 0) {
    Material m;
    m.baseColor = glm::vec3(0.8f);
    scene.addInstance(scene.addMesh(uvSphere({368.0f, 410.0f, 351.0f}, 80.0f, sphereTris, false)), scene.addMaterial(m),
                      glm::mat4(1.0f));
  }
  scene.addLight(PointLight{{213.0f, 300.0f, 227.0f}, glm::vec3(100000.0f)});
  return Camera::lookAt({278, 273, -800}, {278, 273, 0}, {0, 1, 0}, glm::radians(37.0f), aspect);
}

PassResult render(Renderer& renderer, Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                  int passes) {
  PassResult r;
  for (int i = 0; i < passes; ++i) r = renderer.renderPass(scene, camera, region, fb);
  return r;
}

glm::vec3 meanColour(const FrameBuffer& fb, bool hitOnly) {
  glm::dvec3 sum(0.0);
  std::size_t n = 0;
  for (std::uint32_t y = 0; y < fb.height(); ++y)
    for (std::uint32_t x = 0; x < fb.width(); ++x) {
      glm::vec4 c = fb.colour(x, y);
      if (hitOnly && c.w < 1.0f) continue;
      sum += glm::dvec3(glm::vec3(c));
      ++n;
    }
  return n ? glm::vec3(sum / double(n)) : glm::vec3(0.0f);
}

float meanStandardError(const FrameBuffer& fb) {
  double var = 0.0;
  std::size_t n = std::size_t(fb.width()) * fb.height();
  for (std::uint32_t y = 0; y < fb.height(); ++y)
    for (std::uint32_t x = 0; x < fb.width(); ++x)
      var += double(luminance(fb.variance(Channel::Colour, x, y))) / std::max(1u, fb.sampleCount(x, y));
  return float(std::sqrt(var) / double(n));
}

void writePpm(const std::string& path, const FrameBuffer& fb) {
  std::ofstream out(path, std::ios::binary);
  out << "P6\n" << fb.width() << " " << fb.height() << "\n255\n";
  for (std::uint32_t y = 0; y < fb.height(); ++y)
    for (std::uint32_t x = 0; x < fb.width(); ++x) {
      glm::vec4 c = fb.colour(x, y);
      for (int k = 0; k < 3; ++k) {
        float v = std::pow(std::clamp(c[k], 0.0f, 1.0f), 1.0f / 2.2f);
        out.put(char(std::uint8_t(v * 255.0f + 0.5f)));
      }
    }
}

namespace {
template <class T>
bool same(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}
}  // namespace

bool identical(const FrameBuffer& a, const FrameBuffer& b, std::uint32_t ax, std::uint32_t ay) {
  for (std::uint32_t y = 0; y < b.height(); ++y)
    for (std::uint32_t x = 0; x < b.width(); ++x) {
      std::uint32_t xa = x + ax, ya = y + ay;
      if (a.sampleCount(xa, ya) != b.sampleCount(x, y) || !same(a.colour(xa, ya), b.colour(x, y)) ||
          !same(a.depth(xa, ya), b.depth(x, y)) || !same(a.albedo(xa, ya), b.albedo(x, y)) ||
          !same(a.normal(xa, ya), b.normal(x, y))) {
        return false;
      }
      for (Channel c : {Channel::Colour, Channel::Direct, Channel::Indirect}) {
        if (!same(a.mean(c, xa, ya), b.mean(c, x, y)) || !same(a.variance(c, xa, ya), b.variance(c, x, y)))
          return false;
      }
    }
  return true;
}

}  // namespace tsr::embree::test
