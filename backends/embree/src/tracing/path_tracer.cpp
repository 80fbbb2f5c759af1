// Tracer::tracePath: one path from the eye, vertex by vertex. At each
// vertex: emission seen there (weighted against light sampling), the AOVs
// of the first hit, the next direction sampled from the BSDF with its
// throughput and Russian roulette, direct light (sampleDirect), and the
// bookkeeping that sorts contributions into the filters' buffers.
#include "tracing/delta_lights.hpp"
#include "tracing/delta_tracking.hpp"
#include "tracing/equiangular.hpp"
#include "tracing/media.hpp"
#include "tracing/scattering_point.hpp"
#include "tracing/tracer.hpp"
#include "tsr/embree/phase_function.hpp"

namespace tsr::embree {

namespace {

// MIS weight for an emitter reached by BSDF sampling.
float bsdfHitWeight(LightSampling mode, float bsdfPdf, float lightPdf) {
  if (mode == LightSampling::BsdfOnly) return 1.0f;
  if (mode == LightSampling::LightOnly) return 0.0f;
  return powerHeuristic(bsdfPdf, lightPdf);
}

// MIS weight for an emitter reached by light sampling.
float lightSampleWeight(LightSampling mode, float lightPdf, float bsdfPdf) {
  return mode == LightSampling::LightOnly ? 1.0f : powerHeuristic(lightPdf, bsdfPdf);
}

// The random numbers of one vertex. They are drawn in a fixed order:
// emitter, environment, BSDF (then roulette, when the path goes on).
struct VertexSamples {
  bool emitters = false;  // an emitter triangle is sampled for direct light
  bool environment = false;
  float emitterSelect = 0.0f;
  glm::vec2 emitterPoint{0.0f};
  glm::vec2 environmentDir{0.0f};
  glm::vec2 bsdf{0.0f};
  float bsdfLobe = 0.0f;
};

// Index-matched boundaries a ray may cross between two vertices.
constexpr std::uint32_t kMaxCrossings = 64;

// A segment of a ray through a homogeneous medium whose in-scattered
// direct light is sampled twice, by free-flight distances (then light
// sampling and phase sampling at the point) and by equiangular distances
// towards a point of light, combined by MIS over the distance and the
// light point (Kulla & Fajardo 2012, section 4).
struct MediumSegment {
  glm::vec3 org{0.0f}, dir{0.0f};
  float tMax = 0.0f;
  const Medium* medium = nullptr;
  float t = 0.0f;  // where free flight stopped, once it has

  // The density with which free flight stops at t (sampleFreeFlight: the
  // mean over the channels).
  float freeFlightPdf(float at) const {
    const glm::vec3 sigma = medium->extinction();
    return collisionDensity(sigma, transmittance(sigma, at));
  }
  // The equiangular density of distance `at` towards `light`, over free
  // flight's: the equiangular technique in the free-flight techniques'
  // measure (times its light point's density in solid angle).
  float equiangularOverFreeFlight(float at, const glm::vec3& light) const {
    return Equiangular(org, dir, tMax, light).density(at) / freeFlightPdf(at);
  }
};

// The power heuristic over three techniques, for the first.
float powerHeuristic3(float a, float b, float c) {
  const float d = a * a + b * b + c * c;
  return d > 0.0f && std::isfinite(d) ? a * a / d : 0.0f;
}

// A scattering point inside a medium, as light sampling sees it: the phase
// function in place of a BSDF, and shadow rays leaving from the point itself.
struct MediumPoint {
  glm::vec3 p;
  glm::vec3 in;  // the travel direction of the arriving ray
  float g;
  glm::vec3 eval(const glm::vec3& wi, float* pdf) const {
    const float v = henyeyGreenstein(glm::dot(in, wi), g);
    if (pdf) *pdf = v;
    return glm::vec3(v);
  }
  glm::vec3 spawn(const glm::vec3&) const { return p; }
  glm::vec3 ng{0.0f};  // no surface: the light tree bounds no cosine
  // The segment free flight stopped in, when equiangular sampling shares
  // its direct light.
  const MediumSegment* segment = nullptr;
};

// The point just past an index-matched boundary, on the side `dir` goes to.
glm::vec3 pastBoundary(const SurfaceHit& h, const glm::vec3& dir) {
  const float e = rayEpsilon(h.p);
  return h.p + h.faceNormal * (glm::dot(dir, h.faceNormal) > 0.0f ? e : -e);
}

// A ray crossing the boundary of a closed volume enters it when it goes
// against the face normal (normals point out of closed meshes) and leaves
// it otherwise.
void crossBoundary(MediumStack& stack, const SurfaceHit& h, const glm::vec3& dir) {
  const Material& m = h.instance->material->material;
  if (m.interior) stack.cross({&*m.interior, h.instance}, glm::dot(dir, h.faceNormal) < 0.0f);
}

// Where a path goes from a vertex and with what weight.
struct Continuation {
  bool continues = false;
  BsdfSample bs;
  glm::vec3 dir{0.0f};
  glm::vec3 throughput{0.0f};
  glm::vec3 scale{0.0f};
};

// One path's state and its steps. Classification relative to the first
// non-specular vertex, as pixel filtering needs it: direct is light
// reaching that vertex straight from an emitter (or emission seen through
// perfect specular chains); a path that passes a specular surface after a
// non-specular one is a caustic, the hardest to sample, and is indirect
// however few vertices it has.
class PathWalk {
 public:
  PathWalk(Tracer& tracer, Sampler& sampler, RadianceSample* record)
      : tracer_(tracer),
        scene_(tracer.scene),
        env_(tracer.scene.environment),
        envActive_(!env_.isBlack()),
        media_(tracer.scene.materialMedia || env_.medium()),
        mode_(tracer.settings.lightSampling),
        sampler_(sampler),
        record_(record),
        stack_(env_.medium() ? &*env_.medium() : nullptr) {}

  PixelSample run(glm::vec3 org, glm::vec3 dir, const glm::vec3& camPos, const glm::vec3& forward);

 private:
  void add(const glm::vec3& c, std::uint32_t nonSpecularVertices);
  // Whether light found by BSDF sampling counts in full: at the eye and
  // after a delta lobe, light sampling could not have found it.
  bool unweighted(std::uint32_t depth) const { return depth == 0 || prevDelta_; }
  void addEscaped(const glm::vec3& dir, std::uint32_t depth);
  void addEmitted(const SurfaceHit& h, const ResolvedMaterial& mat, const glm::vec3& dir, float t, std::uint32_t depth);
  bool scatter(const ScatteringPoint& sp, const SurfaceHit& h, const RTCHit& hit, std::uint32_t depth, glm::vec3& org,
               glm::vec3& dir);
  // lobe: whether the scattering picks a lobe (not Lambert, not a phase
  // function); its number is skipped otherwise, not drawn.
  VertexSamples drawSamples(bool delta, bool lobe);
  void recordRadiance(const ScatteringPoint& sp, const Continuation& next);
  void roulette(std::uint32_t depth, bool restart, Continuation& next);
  template <class Point>
  void sampleDirect(const Point& sp, const VertexSamples& u, bool fromField);
  void classify(const BsdfSample& bs, MaterialType type);
  // What of a shadow ray's light arrives: 0 or 1 without media; through
  // media, their transmittance, across index-matched boundaries.
  glm::vec3 shadow(glm::vec3 org, const glm::vec3& dir, float tfar);
  // The medium segment from org along dir up to tMax (a surface, or
  // infinity): its emission, and where the flight ends. True with `at` set
  // when it scatters there.
  bool flyThrough(const MediumAt& m, const glm::vec3& org, const glm::vec3& dir, float tMax, std::uint32_t depth,
                  float& at);
  bool scatterInMedium(const Medium& m, const glm::vec3& p, std::uint32_t depth, glm::vec3& org, glm::vec3& dir);
  // Whether direct light in this segment is also sampled by distance
  // towards the lights: a scattering homogeneous medium, MIS, lights to
  // sample, and a vertex there would still sample them.
  bool equiangularActive(const MediumAt& m, std::uint32_t depth) const;
  // The equiangular technique's sample of the segment's direct light.
  void sampleEquiangular(const MediumSegment& s);

  Tracer& tracer_;
  const SceneState& scene_;
  const Environment& env_;
  const bool envActive_;
  const bool media_;  // any medium in the scene: shadow rays measure transmittance
  const LightSampling mode_;
  Sampler& sampler_;
  RadianceSample* record_;
  MediumStack stack_;
  float travelled_ = 0.0f;  // from the last vertex, across index-matched boundaries
  PixelSample out_;
  std::uint32_t nonSpecular_ = 0;      // non-specular scattering vertices so far
  bool specularAfterDiffuse_ = false;  // a specular vertex followed one of them
  // With a radiance record, throughput restarts at 1 after the first
  // non-specular vertex, so that indirect contributions arrive as the
  // incident radiance there; scale_ carries the weight from the eye to that
  // vertex's outgoing ray (exactly 1 otherwise).
  glm::vec3 scale_{1.0f};
  glm::vec3 throughput_{1.0f};
  float pathLength_ = 0.0f;
  std::uint8_t mask_ = 0;
  float prevPdf_ = 0.0f;
  bool prevDelta_ = true;
  bool aovFinal_ = false;    // the albedo and normal are those of a non-specular surface
  glm::vec3 aovTint_{1.0f};  // the specular surfaces' colours before it
  // The last scattering vertex and its normal (zero in a medium): where
  // light sampling would have picked an emitter the path then hits.
  glm::vec3 prevPoint_{0.0f}, prevNormal_{0.0f};
  // The current segment when equiangular sampling is active in it, and the
  // one the last vertex lay in (for the MIS weight of an emitter the phase
  // function's ray then hits).
  MediumSegment segment_, prevSegment_;
  bool segmentActive_ = false, prevSegmentActive_ = false;
};

PixelSample PathWalk::run(glm::vec3 org, glm::vec3 dir, const glm::vec3& camPos, const glm::vec3& forward) {
  std::uint32_t depth = 0;
  for (std::uint32_t crossings = 0; crossings <= kMaxCrossings;) {
    if (!traceable(org, dir, kInf)) {
      ++tracer_.refused;
      break;
    }
    RTCRayHit rh;
    const bool hit = tracer_.intersect(org, dir, rh);
    if (const MediumAt m = media_ ? stack_.current() : MediumAt{}) {
      float at = 0.0f;
      if (flyThrough(m, org, dir, hit ? rh.ray.tfar : kInf, depth, at)) {
        if (depth >= tracer_.settings.maxDepth) break;
        if (!scatterInMedium(*m.medium, org + at * dir, depth, org, dir)) break;
        ++depth;
        continue;
      }
      if (maxComponent(throughput_) <= 0.0f) break;
    }
    if (!hit) {
      if (envActive_) addEscaped(dir, depth);
      break;
    }
    SurfaceHit h;
    if (!tracer_.surface(org, dir, rh, h)) break;
    if (nonSpecular_ == 0) pathLength_ += rh.ray.tfar;
    const ResolvedMaterial& mat = *h.instance->material;
    if (mat.material.type == MaterialType::Interface) {  // no surface: on, into or out of its medium
      crossBoundary(stack_, h, dir);
      travelled_ += rh.ray.tfar;
      org = pastBoundary(h, dir);
      ++crossings;
      continue;
    }
    const SurfaceParameters at = Tracer::parameters(mat, h.uv);
    if (depth == 0) {  // the first hit's depth and instance
      out_.hit = true;
      out_.depth = glm::dot(h.p - camPos, forward);
      out_.object = std::uint32_t(h.instance - tracer_.scene.views.data());
    }
    if (mat.material.isEmissive() && glm::dot(h.faceNormal, dir) < 0.0f)
      addEmitted(h, mat, dir, travelled_ + rh.ray.tfar, depth);
    // Albedo and normal of the first surface that is not a perfect mirror
    // or clear glass (OIDN's convention: what a mirror shows has the
    // texture and edges a denoiser must keep), tinted by the mirrors before
    // it; the last surface's where the path ends on a mirror.
    if (!aovFinal_) {
      out_.albedo = aovTint_ * at.colour;
      out_.normal = glm::dot(h.ns, dir) > 0.0f ? -h.ns : h.ns;
    }
    if (depth >= tracer_.settings.maxDepth) break;
    const ScatteringPoint sp(h, dir, mat.material, at);
    if (!aovFinal_) {
      aovFinal_ = !sp.bsdf.isDelta();
      aovTint_ *= at.colour;
    }
    if (sp.facesAway() || !scatter(sp, h, rh.hit, depth, org, dir)) break;
    ++depth;
    crossings = 0;
  }
  if (record_) record_->mask = mask_;
  return out_;
}

bool PathWalk::flyThrough(const MediumAt& m, const glm::vec3& org, const glm::vec3& dir, float tMax,
                          std::uint32_t depth, float& at) {
  FreeFlight f;
  segmentActive_ = equiangularActive(m, depth);
  if (segmentActive_) {
    segment_ = MediumSegment{org, dir, tMax, m.medium};
    sampleEquiangular(segment_);
  }
  if (m.field()) {
    auto emit = [&](const glm::vec3& e) {
      if (maxComponent(e) > 0.0f) add(throughput_ * e, nonSpecular_);
    };
    f = deltaTrack(
        FieldRay(m, org, dir), tMax, [&] { return sampler_.uniform(); }, emit);
  } else {
    const glm::vec3 emitted = segmentEmission(*m.medium, tMax);
    if (maxComponent(emitted) > 0.0f) add(throughput_ * emitted, nonSpecular_);
    const float uChannel = sampler_.uniform(), uDistance = sampler_.uniform();
    f = sampleFreeFlight(*m.medium, tMax, uChannel, uDistance);
  }
  throughput_ *= f.weight;
  if (!f.scattered) return false;
  if (nonSpecular_ == 0) pathLength_ += f.t;
  at = f.t;
  segment_.t = f.t;
  return true;
}

bool PathWalk::equiangularActive(const MediumAt& m, std::uint32_t depth) const {
  return tracer_.settings.equiangular && mode_ == LightSampling::Mis && !m.field() &&
         maxComponent(m.medium->scattering) > 0.0f && depth < tracer_.settings.maxDepth &&
         (!scene_.emitters.empty() || !scene_.activeLights.empty());
}

// A distance drawn towards one emitter point (picked at the segment's start)
// and towards each point and spot light, each behind a shadow ray, weighted
// against the free-flight techniques that reach the same light.
void PathWalk::sampleEquiangular(const MediumSegment& s) {
  const float uPick = sampler_.uniform();
  const glm::vec2 uPoint = sampler_.uniform2();
  const float uDistance = sampler_.uniform();
  const Medium& m = *s.medium;
  const glm::vec3 sigma = m.extinction();
  auto inScattered = [&](float t) { return throughput_ * transmittance(sigma, t) * m.scattering; };

  std::uint32_t i = 0;
  float prob = 0.0f;
  if (!scene_.emitters.empty() && tracer_.pickEmitter(s.org, glm::vec3(0.0f), uPick, i, prob)) {
    const EmitterTriangle& tri = scene_.emitterTriangles[i];
    const glm::vec2 b = sampleTriangle(uPoint);
    const Equiangular eq(s.org, s.dir, s.tMax, tri.p0 + b.x * tri.e1 + b.y * tri.e2);
    float pdfT = 0.0f;
    const float t = eq.valid() ? eq.sample(uDistance, &pdfT) : 0.0f;
    Tracer::EmitterSample es;
    if (pdfT > 0.0f && tracer_.emitterPoint(s.org + t * s.dir, i, prob, b, es)) {
      const MediumPoint point{s.org + t * s.dir, s.dir, m.g};
      float phasePdf = 0.0f;
      const glm::vec3 f = point.eval(es.wi, &phasePdf);
      const ShadowRay ray = shadowRayTo(point, es.point, es.wi);
      const glm::vec3 seen = shadow(ray.org, ray.dir, ray.tfar);
      if (maxComponent(seen) > 0.0f) {
        // In the free-flight techniques' measure: solid angle at the point,
        // times the distance density over free flight's.
        const float light =
            tracer_.emitterSolidAnglePdf(point.p, glm::vec3(0.0f), i, es.dist, glm::dot(tri.normal, -es.wi));
        const float self = es.pdf * pdfT / s.freeFlightPdf(t);
        const float w = powerHeuristic3(self, light, phasePdf);
        if (w > 0.0f) add(inScattered(t) * f * es.radiance * seen * (w / (es.pdf * pdfT)), nonSpecular_ + 1);
      }
    }
  }
  for (const Light& light : scene_.activeLights) {
    const std::optional<glm::vec3> position = lightPosition(light);
    if (!position) continue;
    const Equiangular eq(s.org, s.dir, s.tMax, *position);
    if (!eq.valid()) continue;
    float pdfT = 0.0f;
    const float t = eq.sample(uDistance, &pdfT);
    LightArrival a;
    const MediumPoint point{s.org + t * s.dir, s.dir, m.g};
    if (!(pdfT > 0.0f) || !lightArriving(light, point.p, a)) continue;
    const glm::vec3 f = point.eval(a.wi, nullptr);
    const glm::vec3 seen = shadow(point.p, a.wi, a.tfar);
    const float w = powerHeuristic(pdfT, s.freeFlightPdf(t));
    if (maxComponent(seen) > 0.0f) add(inScattered(t) * f * a.li * seen * (w / pdfT), nonSpecular_ + 1);
  }
}

// A scattering event in a medium: light sampled through the phase
// function, then the next direction drawn from it (weight 1: the phase
// function is its own density).
bool PathWalk::scatterInMedium(const Medium& m, const glm::vec3& p, std::uint32_t depth, glm::vec3& org,
                               glm::vec3& dir) {
  const VertexSamples u = drawSamples(false, false);
  MediumPoint point{p, dir, m.g};
  if (segmentActive_) point.segment = &segment_;
  Continuation next;
  next.continues = true;
  next.dir = sampleHenyeyGreenstein(dir, m.g, u.bsdf);
  next.bs.pdf = henyeyGreenstein(glm::dot(dir, next.dir), m.g);
  next.bs.weight = glm::vec3(1.0f);
  next.bs.delta = false;
  roulette(depth, false, next);
  sampleDirect(point, u, false);
  if (!next.continues) return false;
  classify(next.bs, MaterialType::Diffuse);
  throughput_ = next.throughput;
  scale_ = next.scale;
  prevPdf_ = next.bs.pdf;
  prevDelta_ = false;
  prevPoint_ = p;
  prevNormal_ = glm::vec3(0.0f);
  prevSegment_ = segment_;
  prevSegmentActive_ = segmentActive_;
  travelled_ = 0.0f;
  org = p;
  dir = next.dir;
  return true;
}

glm::vec3 PathWalk::shadow(glm::vec3 org, const glm::vec3& dir, float tfar) {
  if (!media_) return tracer_.occluded(org, dir, tfar) ? glm::vec3(0.0f) : glm::vec3(1.0f);
  MediumStack stack = stack_;
  glm::vec3 passed(1.0f);
  for (std::uint32_t i = 0; i <= kMaxCrossings; ++i) {
    RTCRayHit rh;
    if (!traceable(org, dir, tfar)) return glm::vec3(0.0f);
    const bool hit = tracer_.intersect(org, dir, rh, tfar);
    const float segment = hit ? rh.ray.tfar : tfar;
    if (const MediumAt m = stack.current())
      passed *= m.field() ? ratioTrack(FieldRay(m, org, dir), segment, [&] { return sampler_.uniform(); })
                          : transmittance(m.medium->extinction(), segment);
    if (!hit) return passed;
    SurfaceHit h;
    if (!tracer_.surface(org, dir, rh, h) || h.instance->material->material.type != MaterialType::Interface)
      return glm::vec3(0.0f);
    if (maxComponent(passed) <= 0.0f) return passed;
    crossBoundary(stack, h, dir);
    org = pastBoundary(h, dir);
    tfar -= segment;
  }
  return glm::vec3(0.0f);
}

void PathWalk::add(const glm::vec3& c, std::uint32_t nonSpecularVertices) {
  if (!finite(c)) return;  // a NaN sample would poison the running mean forever
  const glm::vec3 v = c * scale_;
  if (specularAfterDiffuse_ || nonSpecularVertices > 1) {
    out_.indirect += v;
    if (specularAfterDiffuse_) out_.caustic += v;
    if (record_ && !specularAfterDiffuse_) record_->radiance += c;
  } else {
    out_.direct += v;
    if (nonSpecularVertices == 0) out_.emitted += v;
  }
}

// The environment seen where the path leaves the scene.
void PathWalk::addEscaped(const glm::vec3& dir, std::uint32_t depth) {
  float w = unweighted(depth) ? 1.0f : bsdfHitWeight(mode_, prevPdf_, env_.pdf(dir));
  add(throughput_ * env_.radiance(dir) * w, nonSpecular_);
}

// Emission of the surface the path hit, seen from its front.
void PathWalk::addEmitted(const SurfaceHit& h, const ResolvedMaterial& mat, const glm::vec3& dir, float t,
                          std::uint32_t depth) {
  float w = 1.0f;
  if (!unweighted(depth)) {
    const float light = tracer_.emitterPdf(h, dir, t, prevPoint_, prevNormal_);
    if (prevSegmentActive_) {  // the equiangular technique could have found it too
      const MediumSegment& s = prevSegment_;
      const float eq = s.equiangularOverFreeFlight(s.t, h.p) * tracer_.emitterPdf(h, dir, t, s.org, glm::vec3(0.0f));
      w = powerHeuristic3(prevPdf_, light, eq);
    } else {
      w = bsdfHitWeight(mode_, prevPdf_, light);
    }
  }
  add(throughput_ * Tracer::emission(mat, h.uv) * w, nonSpecular_);
}

// One scattering vertex; false when the path ends there, else org and dir
// become the next segment's. The continuation is computed before the
// shadow rays are traced: it does not depend on them, and its chain of
// square roots, divisions and sincos then runs while Embree traverses,
// instead of after it (out-of-order execution does not reach past the
// mispredicted branches of a traversal into the code that follows the call).
bool PathWalk::scatter(const ScatteringPoint& sp, const SurfaceHit& h, const RTCHit& hit, std::uint32_t depth,
                       glm::vec3& org, glm::vec3& dir) {
  const VertexSamples u = drawSamples(sp.bsdf.isDelta(), sp.bsdf.type != MaterialType::Diffuse);
  Continuation next;
  next.continues = sp.sample(u.bsdf, u.bsdfLobe, next.bs, next.dir);
  const bool nextEvent = !sp.bsdf.isDelta();
  // A delta lobe sampled at a vertex that also has smooth lobes (a clear
  // coat over diffuse) continues the specular chain: the record waits for
  // the next non-specular vertex, as behind a mirror.
  const bool recordHere = record_ && nextEvent && nonSpecular_ == 0 && !(next.continues && next.bs.delta);
  const bool fromField = tracer_.irradiance && nonSpecular_ == 0 && sp.bsdf.closest() == MaterialType::Diffuse;
  if (recordHere) recordRadiance(sp, next);
  roulette(depth, recordHere, next);
  const glm::vec3 nextOrg = sp.spawn(next.dir);

  if (nextEvent) sampleDirect(sp, u, fromField);
  if (fromField) {
    const auto inst = std::uint32_t(h.instance - scene_.views.data());
    add(throughput_ * sp.bsdf.colour * kInvPi * tracer_.irradiance->at(inst, h.prim, hit.u, hit.v), nonSpecular_ + 2);
    return false;
  }
  if (!next.continues) return false;
  classify(next.bs, sp.bsdf.closest());
  // Through a surface with a volume behind it: into or out of that volume.
  if (media_ && glm::dot(dir, h.faceNormal) * glm::dot(next.dir, h.faceNormal) > 0.0f) crossBoundary(stack_, h, dir);
  throughput_ = next.throughput;
  scale_ = next.scale;
  prevPdf_ = next.bs.pdf;
  prevDelta_ = next.bs.delta;
  prevPoint_ = sp.p;
  prevNormal_ = sp.ng;
  prevSegmentActive_ = false;
  travelled_ = 0.0f;
  org = nextOrg;
  dir = next.dir;
  return true;
}

VertexSamples PathWalk::drawSamples(bool delta, bool lobe) {
  VertexSamples u;
  const bool sampleLights = !delta && mode_ != LightSampling::BsdfOnly;
  u.emitters = sampleLights && !scene_.emitters.empty();
  u.environment = sampleLights && envActive_;
  if (u.emitters) {
    u.emitterSelect = sampler_.uniform();
    u.emitterPoint = sampler_.uniform2();
  }
  if (u.environment) u.environmentDir = sampler_.uniform2();
  u.bsdf = sampler_.uniform2();
  if (lobe)
    u.bsdfLobe = sampler_.uniform();
  else
    sampler_.skip(1);
  return u;
}

// The radiance sample at the first non-specular vertex.
void PathWalk::recordRadiance(const ScatteringPoint& sp, const Continuation& next) {
  RadianceSample& r = *record_;
  r.valid = true;
  r.position = sp.p;
  r.normal = sp.frame.n;
  r.wo = sp.wo;
  r.wi = next.continues ? next.dir : glm::vec3(0.0f);
  r.pdf = next.continues ? next.bs.pdf : 0.0f;
  r.throughput = throughput_;
  r.distance = pathLength_;
  r.type = sp.bsdf.type;
  r.colour = sp.bsdf.colour;
  r.alpha = sp.bsdf.alpha;
  r.eta = sp.bsdf.eta;
  r.metallic = sp.bsdf.metallic;
  r.specular = sp.bsdf.specular;
  r.transmission = sp.bsdf.transmission;
}

// The next segment's throughput and scale (restart: a radiance record was
// taken here), then Russian roulette from settings.rouletteDepth on.
void PathWalk::roulette(std::uint32_t depth, bool restart, Continuation& next) {
  next.throughput = throughput_;
  next.scale = scale_;
  if (!next.continues) return;
  if (restart) {
    next.scale = throughput_ * next.bs.weight;
    next.throughput = glm::vec3(1.0f);
  } else {
    next.throughput *= next.bs.weight;
  }
  if (depth + 1 >= tracer_.settings.rouletteDepth) {
    float q = std::min(maxComponent(next.throughput * next.scale), 0.95f);
    if (!(q > 0.0f) || sampler_.uniform() >= q)
      next.continues = false;
    else
      next.throughput /= q;
  }
}

// Direct light at a non-specular vertex (after pbrt-v4's SampleLd): every
// point, spot and directional light, one point on an emitter triangle
// picked by power and one environment direction, each behind a shadow ray;
// the sampled ones weighted against BSDF sampling (not with an irradiance
// field: emitters are found by light sampling alone there).
template <class Point>
void PathWalk::sampleDirect(const Point& sp, const VertexSamples& u, bool fromField) {
  for (const Light& light : scene_.activeLights) {
    LightArrival a;
    if (!lightArriving(light, sp.p, a)) continue;
    glm::vec3 f = sp.eval(a.wi, nullptr);  // delta lights: no MIS
    if (maxComponent(f) <= 0.0f) continue;
    const glm::vec3 seen = shadow(sp.spawn(a.wi), a.wi, a.tfar);
    float w = 1.0f;  // delta lights: no MIS, but for equiangular distances
    if constexpr (std::is_same_v<Point, MediumPoint>)
      if (const std::optional<glm::vec3> position = lightPosition(light); sp.segment && position) {
        const MediumSegment& s = *sp.segment;
        w = powerHeuristic(s.freeFlightPdf(s.t), Equiangular(s.org, s.dir, s.tMax, *position).density(s.t));
      }
    if (maxComponent(seen) > 0.0f) add(throughput_ * f * a.li * seen * w, nonSpecular_ + 1);
  }
  if (u.emitters) {
    Tracer::EmitterSample es;
    if (tracer_.sampleEmitter(sp.p, sp.ng, u.emitterSelect, u.emitterPoint, es)) {
      float bsdfPdf;
      glm::vec3 f = sp.eval(es.wi, &bsdfPdf);
      if (maxComponent(f) > 0.0f) {
        const ShadowRay ray = shadowRayTo(sp, es.point, es.wi);
        const glm::vec3 seen = shadow(ray.org, ray.dir, ray.tfar);
        if (maxComponent(seen) > 0.0f) {
          float w = fromField ? 1.0f : lightSampleWeight(mode_, es.pdf, bsdfPdf);
          if constexpr (std::is_same_v<Point, MediumPoint>)
            if (sp.segment) {
              const MediumSegment& s = *sp.segment;
              const float cosL = glm::dot(scene_.emitterTriangles[es.triangle].normal, -es.wi);
              const float fromStart = tracer_.emitterSolidAnglePdf(s.org, glm::vec3(0.0f), es.triangle, es.dist, cosL);
              w = powerHeuristic3(es.pdf, bsdfPdf, s.equiangularOverFreeFlight(s.t, es.point) * fromStart);
            }
          add(throughput_ * f * es.radiance * seen * (w / es.pdf), nonSpecular_ + 1);
        }
      }
    }
  }
  if (u.environment) {
    Environment::Sample es = env_.sample(u.environmentDir);
    if (es.pdf > 0.0f) {
      float bsdfPdf;
      glm::vec3 f = sp.eval(es.direction, &bsdfPdf);
      const glm::vec3 seen =
          maxComponent(f) > 0.0f ? shadow(sp.spawn(es.direction), es.direction, kInf) : glm::vec3(0.0f);
      if (maxComponent(seen) > 0.0f) {
        const float w = fromField ? 1.0f : lightSampleWeight(mode_, es.pdf, bsdfPdf);
        add(throughput_ * f * es.radiance * seen * (w / es.pdf), nonSpecular_ + 1);
      }
    }
  }
}

// What the path's next segment counts as for the filters: the mask of
// specular first vertices, caustic paths, non-specular vertices so far.
void PathWalk::classify(const BsdfSample& bs, MaterialType type) {
  if (bs.delta && nonSpecular_ == 0) {
    mask_ |= kMaskSpecular;
    if (type == MaterialType::Glass) mask_ |= kMaskReflectRefract;
  }
  if (bs.delta)
    specularAfterDiffuse_ = specularAfterDiffuse_ || nonSpecular_ > 0;
  else
    ++nonSpecular_;
}

}  // namespace

PixelSample Tracer::tracePath(Sampler& sampler, glm::vec3 org, glm::vec3 dir, const glm::vec3& camPos,
                              const glm::vec3& forward, RadianceSample* record) {
  return PathWalk(*this, sampler, record).run(org, dir, camPos, forward);
}

}  // namespace tsr::embree
