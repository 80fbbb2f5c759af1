#pragma once
// Scenes and helpers shared by the Vulkan mediator tests.
#include <string>

#include "../viewport_rig.hpp"
#include "tsr/med/frame_buffer.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::test {

// A quad with corners a, b, c, d, counter-clockwise seen from its front.
sg::Geometry& addQuad(sg::Scene& scene, sg::ContainerId parent, const std::string& name, sg::Vec3 a, sg::Vec3 b,
                      sg::Vec3 c, sg::Vec3 d, sg::ContainerId material);
// An axis-aligned box with outward faces.
sg::Geometry& addBox(sg::Scene& scene, sg::ContainerId parent, const std::string& name, sg::Vec3 lo, sg::Vec3 hi,
                     sg::ContainerId material);
// A UV sphere with smooth normals.
sg::Geometry& addSphere(sg::Scene& scene, sg::ContainerId parent, const std::string& name, sg::Vec3 centre,
                        float radius, int segments, sg::ContainerId material);

// Writes `image` as DIR/NAME.png when TSR_TEST_IMAGE_DIR is set, to look at.
void keepImage(const std::string& name, const med::FrameBuffer& image);

}  // namespace tsr::test
