#include "tsr/embree/probe_tracing.hpp"

#include "tracing/tracer.hpp"
#include "tsr/embree/error.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>

namespace tsr::embree {

namespace {

using backend::IrradianceVolume;

// The probes' random streams, apart from the camera paths'.
constexpr std::uint64_t kProbeStream = 0xBB67AE8584CAA73Bull;

// Adds perTexel rounds of paths to the probe's sums, a round being one path
// through each texel of its distance map: texel t's path of round r is
// Sobol sample r of the stream keyed by (probe, t), so each texel's paths
// are stratified over rounds, and rounds are summed in order whatever the
// calls that trace them.
void traceProbe(Tracer& tracer, const RenderSettings& settings, const IrradianceVolume& volume, std::size_t probe,
                std::uint32_t perTexel, ProbeSums& sums) {
  constexpr std::uint32_t side = IrradianceVolume::kDistanceSide;
  const glm::vec3 org = volume.probePosition(probe);
  // Shading points lie within a cell of a probe: farther distances decide nothing.
  const float farthest = 1.5f * glm::length(volume.cellSize()) + 1e-6f;
  const std::uint32_t first = sums.paths / IrradianceVolume::kDistanceTexels;
  for (std::uint32_t round = first; round < first + perTexel; ++round) {
    for (std::uint32_t texel = 0; texel < IrradianceVolume::kDistanceTexels; ++texel) {
      const std::uint64_t key =
          Rng::pixelKey(settings.seed ^ kProbeStream, std::uint32_t(probe), texel + (std::uint32_t(probe >> 32) << 6));
      Sampler sampler(settings.sampler, key, round);
      const glm::vec2 corner(float(texel % side), float(texel / side));
      const glm::vec3 dir = backend::equalAreaSquareToSphere((corner + sampler.uniform2()) / float(side));
      float distance = farthest;
      bool throughBoundary = false;  // the first hit is a medium's boundary
      glm::vec3 straight(0.0f);      // emission of the first surface, seen from its front
      RTCRayHit rh;
      if (tracer.intersect(org, dir, rh)) {
        distance = std::min(rh.ray.tfar, farthest);
        SurfaceHit h;
        if (tracer.surface(org, dir, rh, h)) {
          const ResolvedMaterial& mat = *h.instance->material;
          const float facing = glm::dot(h.faceNormal, dir);
          if (facing > 0.0f) ++sums.backFaces;
          throughBoundary = mat.material.type == MaterialType::Interface;
          if (!throughBoundary && facing < 0.0f && mat.material.isEmissive()) straight = Tracer::emission(mat, h.uv);
        }
      }
      sums.distance[texel] += glm::vec2(distance, distance * distance);
      const PixelSample s = tracer.tracePath(sampler, org, dir, org, dir);
      // Emitters seen straight are the reader's own lights. Only those: a
      // lamp seen in a mirror or through glass is light the reader cannot
      // make (its caustic on the surfaces round the probe). Past a medium's
      // boundary the path's emission seen without scattering stands in.
      glm::vec3 radiance = s.direct + s.indirect - (throughBoundary ? s.emitted : straight);
      if (!finite(radiance)) continue;
      radiance = glm::max(radiance, glm::vec3(0.0f));
      const auto cosines = backend::faceCosines(dir);
      for (std::uint32_t i = 0; i < IrradianceVolume::kFaces; ++i) sums.faces[i] += radiance * cosines[i];
    }
  }
  sums.paths += perTexel * IrradianceVolume::kDistanceTexels;
}

// The probe's values from its sums.
void writeProbe(const ProbeSums& sums, std::size_t probe, IrradianceVolume& volume) {
  if (sums.paths == 0) return;
  // Uniform directions: each path stands for 4 pi / paths of solid angle.
  const float perPath = 4.0f * kPi / float(sums.paths);
  const float weight = sums.backFaces * 4 > sums.paths ? 0.0f : 1.0f;
  for (std::uint32_t i = 0; i < IrradianceVolume::kFaces; ++i)
    volume.irradiance[probe * IrradianceVolume::kFaces + i] =
        glm::vec4(sums.faces[i] * perPath, i == 0 ? weight : 0.0f);
  const float perTexel = float(sums.paths / IrradianceVolume::kDistanceTexels);
  for (std::uint32_t t = 0; t < IrradianceVolume::kDistanceTexels; ++t)
    volume.distance[probe * IrradianceVolume::kDistanceTexels + t] = sums.distance[t] / perTexel;
}

}  // namespace

std::uint64_t traceProbes(Scene& scene, const RenderSettings& settings, IrradianceVolume& volume,
                          std::vector<ProbeSums>& sums, std::size_t first, std::size_t count, std::uint32_t paths) {
  const std::size_t probes = volume.probeCount();
  if (probes == 0 || count == 0) return 0;
  if (volume.irradiance.size() != probes * IrradianceVolume::kFaces ||
      volume.distance.size() != probes * IrradianceVolume::kDistanceTexels || sums.size() != probes)
    throw Error("irradiance volume's arrays or sums do not match its " + std::to_string(probes) + " probes");
  count = std::min(count, probes);
  const std::uint32_t perTexel =
      std::max(1u, (paths + IrradianceVolume::kDistanceTexels - 1) / IrradianceVolume::kDistanceTexels);
  scene.commit();
  const SceneState& state = scene.state();
  std::vector<std::uint64_t> rays(count, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const std::size_t probe = (first + i) % probes;
      Tracer tracer{state, settings};
      traceProbe(tracer, settings, volume, probe, perTexel, sums[probe]);
      writeProbe(sums[probe], probe, volume);
      rays[i] = tracer.rays;
    }
  });
  ++volume.version;
  std::uint64_t total = 0;
  for (auto r : rays) total += r;
  return total;
}

}  // namespace tsr::embree
