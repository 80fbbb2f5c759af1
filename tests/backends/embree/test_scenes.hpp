#pragma once

#include "tsr/embree/framebuffer.hpp"
#include "tsr/embree/renderer.hpp"
#include "tsr/embree/sampling.hpp"
#include "tsr/embree/scene.hpp"

#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>

#include <memory>
#include <string>

namespace tsr::embree::test {

std::shared_ptr<Device> sharedDevice();

// UV sphere built like tests/bench/scenes/make_cornell.py: about `tris`
// triangles; smooth normals only when asked for.
MeshData uvSphere(const glm::vec3& centre, float radius, int tris, bool normals);
// An axis-aligned box, closed, faces wound counter-clockwise seen from
// outside (normals out).
MeshData box(const glm::vec3& lo, const glm::vec3& hi);
// Two triangles p0 p1 p2, p0 p2 p3 (counter-clockwise seen from the front), uvs 0..1.
MeshData quad(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3);

// The Cornell box of make_cornell.py (per-colour meshes and its point
// light), optionally with its tessellated sphere; returns its camera.
Camera cornellBox(Scene& scene, int sphereTris, float aspect = 1.0f);

// A grey 10x10 floor at y = 0 under a 2x2 lamp (emission 20) at y = 5.
void floorUnderLamp(Scene& scene);

// A unit sphere filled with `medium` (index-matched boundary) in a
// constant environment of 0.5, seen whole at 24x24, 256 spp, paths up to
// 1000 vertices: the mean of the frame (a white medium gives 0.5 back).
glm::vec3 furnaceMean(Scene& scene, const Medium& medium);

// Renders `passes` passes and returns the last result.
PassResult render(Renderer& renderer, Scene& scene, const Camera& camera, const Region& region, FrameBuffer& fb,
                  int passes);

// Mean radiance over pixels; with hitOnly, over pixels whose every camera sample hit.
glm::vec3 meanColour(const FrameBuffer& fb, bool hitOnly = false);
// Standard error of meanColour(fb) (luminance), from the per-pixel variances.
float meanStandardError(const FrameBuffer& fb);

void writePpm(const std::string& path, const FrameBuffer& fb);

// Exact equality of every output of two frame buffers (or of a crop of a).
bool identical(const FrameBuffer& a, const FrameBuffer& b, std::uint32_t ax = 0, std::uint32_t ay = 0);

}  // namespace tsr::embree::test
