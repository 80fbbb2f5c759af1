#include "photons/photon_pass.hpp"

#include "tracing/delta_lights.hpp"
#include "tracing/scattering_point.hpp"
#include "tracing/tracer.hpp"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/partitioner.h>

#include <variant>

namespace tsr::embree {

namespace {

// A light or emissive triangle and the power it is chosen by.
struct Source {
  enum Kind { Point, Spot, Directional, Triangle } kind;
  std::uint32_t index;  // into activeLights or emitterTriangles
  glm::vec3 power;
  glm::vec3 emission{0.0f};  // triangles: radiance leaving the front face
};

struct Disc {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
};

Disc coveringDisc(const ElementGeometry& g) {
  return {0.5f * (g.lower + g.upper), std::max(1e-6f, 0.5f * glm::length(g.upper - g.lower))};
}

float coneSolidAngle(float halfAngle) { return 2.0f * kPi * (1.0f - std::cos(halfAngle)); }

std::vector<Source> sources(const SceneState& scene, const ElementGeometry& bounds) {
  std::vector<Source> out;
  const Disc disc = coveringDisc(bounds);
  for (std::uint32_t i = 0; i < scene.activeLights.size(); ++i) {
    const Light& l = scene.activeLights[i];
    if (const auto* p = std::get_if<PointLight>(&l))
      out.push_back({Source::Point, i, 4.0f * kPi * p->intensity});
    else if (const auto* s = std::get_if<SpotLight>(&l))
      out.push_back({Source::Spot, i, coneSolidAngle(s->outerAngle) * s->intensity});
    else
      out.push_back(
          {Source::Directional, i, kPi * disc.radius * disc.radius * std::get<DirectionalLight>(l).irradiance});
  }
  for (const EmissiveRange& r : scene.emissiveRanges) {
    const InstanceView& v = scene.views[r.instance];
    const glm::vec3 e = v.material->material.emission;  // emission textures are not sampled for photons
    const std::uint32_t count = std::uint32_t(v.mesh->indices.size() / 3);
    for (std::uint32_t t = 0; t < count; ++t) {
      const EmitterTriangle& tri = scene.emitterTriangles[r.offset + t];
      out.push_back({Source::Triangle, r.offset + t, kPi * tri.area * e, e});
    }
  }
  return out;
}

struct Emission {
  glm::vec3 org, dir, power;  // power relative to the source's selection power
};

bool emit(const SceneState& scene, const Source& s, const Disc& disc, Rng& rng, Emission& out) {
  const glm::vec2 u = rng.uniform2();
  switch (s.kind) {
    case Source::Point:
      out.org = std::get<PointLight>(scene.activeLights[s.index]).position;
      out.dir = sampleUniformSphere(u);
      out.power = glm::vec3(1.0f);
      return true;
    case Source::Spot: {
      const auto& sl = std::get<SpotLight>(scene.activeLights[s.index]);
      const float c = 1.0f - u.x * (1.0f - std::cos(sl.outerAngle));  // uniform in the cone
      const float r = std::sqrt(std::max(0.0f, 1.0f - c * c));
      const Frame f(glm::normalize(sl.direction));
      out.org = sl.position;
      out.dir = f.toWorld({r * std::cos(2.0f * kPi * u.y), r * std::sin(2.0f * kPi * u.y), c});
      out.power = glm::vec3(spotFalloff(sl, c));
      return out.power.x > 0.0f;
    }
    case Source::Directional: {
      const Frame f(glm::normalize(std::get<DirectionalLight>(scene.activeLights[s.index]).direction));
      const float r = disc.radius * std::sqrt(u.x), phi = 2.0f * kPi * u.y;
      out.dir = f.n;
      out.org = disc.centre - 2.0f * disc.radius * f.n + f.toWorld({r * std::cos(phi), r * std::sin(phi), 0.0f});
      out.power = glm::vec3(1.0f);
      return true;
    }
    case Source::Triangle: {
      const EmitterTriangle& tri = scene.emitterTriangles[s.index];
      if (!(tri.area > 0.0f)) return false;
      const glm::vec2 b = sampleTriangle(u);
      out.org = tri.p0 + b.x * tri.e1 + b.y * tri.e2;
      out.dir = Frame(tri.normal).toWorld(sampleCosineHemisphere(rng.uniform2()));
      out.org += tri.normal * rayEpsilon(out.org);
      out.power = glm::vec3(1.0f);
      return true;
    }
  }
  return false;
}

// A photon leaving its source.
struct Photon {
  glm::vec3 org, dir, power;
  std::uint32_t parity;  // its half-set, PhotonHit::parity
};

// Follows one photon through the scene: every hit on a Diffuse surface
// after the first scattering is recorded.
void follow(Tracer& tracer, const ElementSet& elements, std::uint32_t maxBounces, Rng& rng, const Photon& photon,
            std::vector<PhotonHit>& hits) {
  glm::vec3 org = photon.org, dir = photon.dir, power = photon.power;
  bool scattered = false;
  for (std::uint32_t bounce = 0; bounce <= maxBounces; ++bounce) {
    RTCRayHit rh;
    if (!traceable(org, dir, kInf) || !tracer.intersect(org, dir, rh)) break;
    SurfaceHit h;
    if (!tracer.surface(org, dir, rh, h)) break;
    const ResolvedMaterial& mat = *h.instance->material;
    const SurfaceParameters at = Tracer::parameters(mat, h.uv);
    // Stored where the diffuse lobe dominates, as on Diffuse surfaces.
    if (scattered &&
        closestClass(mat.material.type, at.roughness, at.metallic, at.transmission) == MaterialType::Diffuse) {
      const auto inst = std::uint32_t(h.instance - tracer.scene.views.data());
      const std::uint32_t el = elements.locate(inst, h.prim, rh.hit.u, rh.hit.v, nullptr);
      if (el != kNoElement && finite(power)) hits.push_back({el, photon.parity, power});
    }
    if (bounce == maxBounces) break;
    const ScatteringPoint sp(h, dir, mat.material, at);
    if (sp.facesAway()) break;
    const glm::vec2 u = rng.uniform2();
    const float uLobe = rng.uniform();
    BsdfSample bs;
    glm::vec3 next(0.0f);
    if (!sp.sample(u, uLobe, bs, next)) break;
    // Roulette by the weight's largest channel keeps photon energies even.
    const float q = std::min(1.0f, maxComponent(bs.weight));
    if (!(q > 0.0f) || rng.uniform() >= q) break;
    power *= bs.weight / q;
    org = sp.spawn(next);
    dir = next;
    scattered = true;
  }
}

const RenderSettings kPhotonSettings{};  // the Tracer reads none of it for photons
constexpr std::uint64_t kBlock = 4096;

}  // namespace

std::vector<glm::vec3> sourcePowers(const SceneState& scene, const ElementGeometry& bounds) {
  std::vector<glm::vec3> out;
  for (const Source& s : sources(scene, bounds)) out.push_back(s.power);
  return out;
}

glm::vec3 emittedPower(const SceneState& scene, const ElementGeometry& bounds) {
  glm::vec3 sum(0.0f);
  for (const glm::vec3& p : sourcePowers(scene, bounds)) sum += p;
  return sum;
}

PhotonPassResult tracePhotons(const SceneState& scene, const ElementSet& elements, const ElementGeometry& geometry,
                              std::uint64_t photons, std::uint64_t streamKey, std::uint32_t maxBounces,
                              tbb::task_arena& arena) {
  PhotonPassResult result;
  const std::vector<Source> src = sources(scene, geometry);
  std::vector<float> weights;
  for (const Source& s : src) weights.push_back(luminance(s.power));
  const Distribution1D pick(weights);
  if (pick.empty() || photons == 0) return result;
  const Disc disc = coveringDisc(geometry);
  const std::size_t blocks = std::size_t((photons + kBlock - 1) / kBlock);
  std::vector<std::vector<PhotonHit>> blockHits(blocks);
  std::vector<std::uint64_t> blockRays(blocks, 0);

  auto traceBlock = [&](std::size_t block) {
    Tracer tracer{scene, kPhotonSettings};
    std::vector<PhotonHit>& hits = blockHits[block];
    const std::uint64_t end = std::min(photons, (block + 1) * kBlock);
    for (std::uint64_t i = block * kBlock; i < end; ++i) {
      Rng rng(streamKey, i);
      float prob = 0.0f;
      const Source& s = src[pick.sampleDiscrete(rng.uniform(), &prob)];
      Emission e;
      if (!(prob > 0.0f) || !emit(scene, s, disc, rng, e)) continue;
      const glm::vec3 power = e.power * s.power / (prob * float(photons));
      follow(tracer, elements, maxBounces, rng, {e.org, e.dir, power, std::uint32_t(i & 1)}, hits);
    }
    blockRays[block] = tracer.rays;
  };

  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, blocks, 1),
        [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t b = r.begin(); b != r.end(); ++b) traceBlock(b);
        },
        tbb::simple_partitioner());
  });
  for (std::size_t b = 0; b < blocks; ++b) {
    result.hits.insert(result.hits.end(), blockHits[b].begin(), blockHits[b].end());
    result.rays += blockRays[b];
  }
  return result;
}

}  // namespace tsr::embree
