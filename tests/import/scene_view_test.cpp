// What programs do to a scene before showing it (tsr/sg/import/
// scene_camera.hpp, default_light_rig.hpp): pick or make the camera, apply
// the user's placement, and light a scene that brings no light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "tsr/sg/import/default_light_rig.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/import/scene_camera.hpp"
#include "tsr/sg/node_world.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::sg {
namespace {

// A unit box of triangles under a Transform at (10, 0, 0), in a root group.
struct BoxScene {
  Scene scene;
  ContainerId root, background;
  BoxScene() {
    auto& group = scene.create<Group>("root");
    auto& place = scene.create<Transform>("place");
    place.setMatrix(glm::translate(Mat4(1.0f), Vec3(10, 0, 0)));
    auto& box = scene.create<Geometry>("box");
    box.setPositions({{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, 1}});
    box.setIndices({0, 1, 2, 0, 2, 3});
    box.setMaterial(scene.create<SurfaceMaterial>("grey").id());
    place.addChild(box.id());
    group.addChild(place.id());
    root = group.id();
    background = scene.create<Background>("background").id();
  }
  ContainerId camera(const std::string& name, const Vec3& eye) {
    auto& c = scene.create<Camera>(name);
    c.lookAt(eye, Vec3(10, 0, 0));
    return c.id();
  }
};

LookOverride lookOf(std::optional<Vec3> from, std::optional<Vec3> at, std::optional<float> fov) {
  LookOverride look;
  look.from = from;
  look.at = at;
  look.fovDegrees = fov;
  return look;
}

Vec3 position(const Scene& s, ContainerId camera) { return Vec3(cameraWorldPose(s, camera)[3]); }

TEST(SceneView, AFramingCameraSeesTheWholeBounds) {
  BoxScene b;
  const ContainerId id = addFramingCamera(b.scene, b.root);
  const Camera& cam = *b.scene.find<Camera>(id);
  const Mat4 view = glm::inverse(cameraWorldPose(b.scene, id));
  for (float x : {9.0f, 11.0f})
    for (float y : {-1.0f, 1.0f})
      for (float z : {-1.0f, 1.0f}) {
        const Vec3 c = Vec3(view * glm::vec4(x, y, z, 1.0f));
        ASSERT_LT(c.z, -cam.nearPlane());
        EXPECT_LT(std::abs(c.y / c.z), std::tan(cam.verticalFov() / 2)) << "corner inside the vertical field";
      }
}

// Navigation sets a camera's place in the world; under a node (builtin:
// cornell's camera hangs under one) the node's transform is undone.
TEST(SceneView, ACameraUnderANodeTakesTheWorldPoseItIsGiven) {
  Scene cornell;
  const ImportResult imported = importScene(cornell, "builtin:cornell");
  Camera& camera = *cornell.find<Camera>(imported.cameras.front());
  const Mat4 wanted = glm::inverse(glm::lookAt(Vec3(-200, 300, -600), Vec3(278, 273, 280), Vec3(0, 1, 0)));
  ASSERT_GT(glm::length(Vec3(cameraWorldPose(cornell, camera.id())[3]) - Vec3(camera.pose()[3])), 1.0f)
      << "the camera should hang under a transform for this test";
  setCameraWorldPose(camera, wanted);
  const Mat4 got = cameraWorldPose(cornell, camera.id());
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(got[c][r], wanted[c][r], 1e-3f) << c << r;
}

TEST(SceneView, CamerasAreChosenByNameOrIndex) {
  BoxScene b;
  const std::vector<ContainerId> cams = {b.camera("near", {10, 0, 5}), b.camera("far", {10, 0, 50}),
                                         b.camera("twin", {0, 0, 5}), b.camera("twin", {20, 0, 5})};
  EXPECT_EQ(chooseCamera(b.scene, cams, "far"), cams[1]);
  EXPECT_EQ(chooseCamera(b.scene, cams, "0"), cams[0]);
  EXPECT_EQ(chooseCamera(b.scene, cams, "3"), cams[3]);
  EXPECT_THROW(chooseCamera(b.scene, cams, "twin"), std::invalid_argument) << "ambiguous name";
  EXPECT_THROW(chooseCamera(b.scene, cams, "4"), std::invalid_argument);
  EXPECT_THROW(chooseCamera(b.scene, cams, "-1"), std::invalid_argument);
  EXPECT_THROW(chooseCamera(b.scene, {}, "0"), std::invalid_argument);
}

TEST(SceneView, LookOverridesPlaceANewCameraOrWidenTheChosenOne) {
  BoxScene b;
  const ContainerId base = b.camera("base", {10, 0, 5});
  const std::size_t before = b.scene.size();
  EXPECT_EQ(applyLookOverride(b.scene, b.root, base, lookOf({}, {}, 90.0f), 1.0f), base);
  EXPECT_NEAR(b.scene.find<Camera>(base)->verticalFov(), glm::radians(90.0f), 1e-6f);
  EXPECT_EQ(b.scene.size(), before) << "a field of view alone makes no camera";

  const ContainerId look = applyLookOverride(b.scene, b.root, base, lookOf(Vec3(10, 8, 0), {}, {}), 1.0f);
  EXPECT_NE(look, base);
  EXPECT_LT(glm::length(position(b.scene, look) - Vec3(10, 8, 0)), 1e-4f);
  const Vec3 forward = -Vec3(cameraWorldPose(b.scene, look)[2]);
  EXPECT_LT(glm::length(forward - Vec3(0, -1, 0)), 1e-4f) << "looks at the bounds' centre, straight down";

  EXPECT_THROW(applyLookOverride(b.scene, b.root, base, lookOf(Vec3(1), Vec3(1), {}), 1.0f), std::invalid_argument);
  EXPECT_THROW(applyLookOverride(b.scene, b.root, base, lookOf({}, {}, 180.0f), 1.0f), std::invalid_argument);
  EXPECT_THROW(applyLookOverride(b.scene, b.root, base, lookOf({}, Vec3(NAN, 0, 0), {}), 1.0f), std::invalid_argument);
}

// builtin:cornell is in millimetres, glTF in metres: an f-number and the
// eyes' separation mean the same physical lens and eyes in both.
TEST(SceneView, PhysicalSettingsFollowTheScenesUnit) {
  Scene cornell;
  const ImportResult imported = importScene(cornell, "builtin:cornell");
  EXPECT_FLOAT_EQ(imported.metresPerUnit, 0.001f);
  const Camera& camera = *cornell.find<Camera>(imported.cameras.front());
  EXPECT_NEAR(camera.eyeSeparation(), 65.0f, 1e-3f) << "65 mm between the eyes";
  LookOverride f2;
  f2.fNumber = 2.0f;
  const ContainerId lens = applyLookOverride(cornell, imported.root, camera.id(), f2, imported.metresPerUnit);
  const float metres = apertureOfFNumber(2.0f, camera.verticalFov());
  EXPECT_NEAR(cornell.find<Camera>(lens)->apertureRadius(), metres * 1000.0f, 1e-3f);
  EXPECT_GT(cornell.find<Camera>(lens)->apertureRadius(), 5.0f) << "f/2 is millimetres wide, not a pinhole";
  EXPECT_THROW(applyLookOverride(cornell, imported.root, camera.id(), f2, 0.0f), std::invalid_argument);

  BoxScene b;
  const ContainerId base = b.camera("base", {10, 0, 5});
  const ContainerId same = applyLookOverride(b.scene, b.root, base, f2, 1.0f);
  EXPECT_FLOAT_EQ(b.scene.find<Camera>(same)->apertureRadius(),
                  apertureOfFNumber(2.0f, b.scene.find<Camera>(base)->verticalFov()));
}

TEST(SceneView, OnlyASceneWithoutLightGetsTheRigAndItsLightFollowsTheCamera) {
  Scene cornell;
  const ImportResult imported = importScene(cornell, "builtin:cornell");
  EXPECT_TRUE(hasOwnLighting(cornell, imported.root, imported.background)) << "its panel emits";

  BoxScene b;
  EXPECT_FALSE(hasOwnLighting(b.scene, b.root, b.background));
  b.scene.find<Background>(b.background)->setColor(Vec3(0.1f));
  EXPECT_TRUE(hasOwnLighting(b.scene, b.root, b.background)) << "a bright background lights it";
  b.scene.find<Background>(b.background)->setColor(Vec3(0.0f));

  const DefaultLightRig rig = addDefaultLightRig(b.scene, b.root, b.background);
  ASSERT_TRUE(rig.active());
  EXPECT_EQ(rig.dome, b.background);
  EXPECT_EQ(b.scene.find<Background>(b.background)->color(), Vec3(kDomeRadiance));
  const auto& children = b.scene.find<Group>(b.root)->children();
  EXPECT_NE(std::find(children.begin(), children.end(), rig.follower), children.end());
  const ContainerId cam = b.camera("cam", {10, 0, 5});
  followCamera(b.scene, rig, cameraWorldPose(b.scene, cam));
  const Mat4 lightWorld = parentWorldMatrix(b.scene, rig.light);
  const Light& light = *b.scene.find<Light>(rig.light);
  EXPECT_EQ(light.kind(), LightKind::Directional);
  const Vec3 shines = glm::normalize(Vec3(lightWorld * glm::vec4(light.direction(), 0.0f)));
  EXPECT_LT(glm::length(shines - Vec3(0, 0, -1)), 1e-5f) << "along the camera's view";
  EXPECT_TRUE(hasOwnLighting(b.scene, b.root, b.background)) << "once rigged, it has lights";
}

}  // namespace
}  // namespace tsr::sg
