// The reflection probe: mirrors show the room around them, rough metals
// show it blurred by their roughness, and the probe is drawn (and
// prefiltered) again only when the scene changed.
#include "test_util.hpp"

#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"

#include <gtest/gtest.h>

namespace tsr::vk {
namespace {

using test::device;
using test::glowing;

// A room [-2, 2]^3 open towards +z: red wall at x = -2, green at x = +2,
// blue at the back, grey floor and ceiling; a mirror sphere (or the given
// material's) off the centre.
Material mirrorMaterial() {
  Material mirror;
  mirror.type = MaterialType::Mirror;
  mirror.baseColor = glm::vec3(1.0f);
  return mirror;
}

struct Room {
  Scene scene{device()};
  MaterialId red, green;
  explicit Room(const Material& sphere = mirrorMaterial(), glm::vec3 at = {0.8f, 0.0f, 0.0f}, float radius = 0.5f) {
    red = scene.addMaterial(glowing({1, 0, 0}));
    green = scene.addMaterial(glowing({0, 1, 0}));
    const MaterialId blue = scene.addMaterial(glowing({0, 0, 1})), grey = scene.addMaterial(glowing(glm::vec3(0.3f)));
    auto wall = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, MaterialId m) {
      scene.addInstance(scene.addMesh(test::quad(a, b, c, d)), m, glm::mat4(1.0f));
    };
    wall({-2, -2, 2}, {-2, -2, -2}, {-2, 2, -2}, {-2, 2, 2}, red);   // faces +x
    wall({2, -2, -2}, {2, -2, 2}, {2, 2, 2}, {2, 2, -2}, green);     // faces -x
    wall({-2, -2, -2}, {2, -2, -2}, {2, 2, -2}, {-2, 2, -2}, blue);  // faces +z
    wall({-2, -2, 2}, {2, -2, 2}, {2, -2, -2}, {-2, -2, -2}, grey);  // floor, faces +y
    wall({-2, 2, -2}, {2, 2, -2}, {2, 2, 2}, {-2, 2, 2}, grey);      // ceiling, faces -y
    scene.addInstance(scene.addMesh(test::uvSphere(32, 64, radius)), scene.addMaterial(sphere),
                      glm::translate(glm::mat4(1.0f), at));
  }
};

// The room from `cam` at 96x96, lit by its glowing walls alone.
FrameBuffer look(Room& room, const Camera& cam) {
  Renderer renderer(device(), {.emitterLights = 0, .emitterAmbient = false});
  FrameBuffer fb(96, 96);
  renderer.render(room.scene, cam, Region::full(96, 96), fb);
  return fb;
}

TEST(VulkanReflectionProbe, MirrorShowsTheWallItFaces) {
  Room room;
  const Camera cam = Camera::lookAt({0.8f, 0, 1.8f}, {0.8f, 0, 0}, {0, 1, 0}, 0.9f, 1.0f);
  const Region full = Region::full(96, 96);
  Renderer renderer(device(), {.emitterLights = 0, .emitterAmbient = false});
  FrameBuffer fb(96, 96);
  renderer.render(room.scene, cam, full, fb);
  test::writePng("/tmp/tsr_vk_probe_mirror.png", fb);
  EXPECT_EQ(renderer.lastStats().probes, 1u);
  // Normals 45 degrees to the left and right: mirrored towards -x and +x.
  const glm::vec2 left = test::project(cam, full, {0.8f - 0.354f, 0, 0.354f});
  const glm::vec2 right = test::project(cam, full, {0.8f + 0.354f, 0, 0.354f});
  const glm::vec4 l = fb.colour(int(left.x), int(left.y)), r = fb.colour(int(right.x), int(right.y));
  EXPECT_GT(l.r, 0.8f) << "the red wall";
  EXPECT_LT(std::max(l.g, l.b), 0.1f);
  EXPECT_GT(r.g, 0.8f) << "the green wall";
  EXPECT_LT(std::max(r.r, r.b), 0.1f);
  // Straight back along the view: the open side, black.
  const glm::vec2 centre = test::project(cam, full, {0.8f, 0, 0.5f});
  EXPECT_LT(fb.colour(int(centre.x), int(centre.y)).g, 0.1f);

  // Unchanged scene: the probe is kept. An edit: drawn again, and it shows.
  renderer.render(room.scene, cam, full, fb);
  EXPECT_EQ(renderer.lastStats().probes, 0u);
  room.scene.setMaterial(room.red, glowing({1, 1, 0}));
  renderer.render(room.scene, cam, full, fb);
  EXPECT_EQ(renderer.lastStats().probes, 1u);
  EXPECT_GT(fb.colour(int(left.x), int(left.y)).g, 0.8f) << "the wall turned yellow";
}

// A yellow ball just right of the room's centre hides the green wall, as
// seen from there, in the direction the mirror's right side reflects: the
// scene's probe alone (box-projected, or searched along the ray) shows
// yellow there. The mirror's own probe, drawn from its centre, sees the
// green wall past it.
TEST(VulkanReflectionProbe, MirrorReflectsFromItsOwnCentre) {
  Room room;
  room.scene.addInstance(room.scene.addMesh(test::uvSphere(16, 32, 0.15f)), room.scene.addMaterial(glowing({1, 1, 0})),
                         glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 0.0f, 0.0f)));
  const Camera cam = Camera::lookAt({0.8f, 0, 1.8f}, {0.8f, 0, 0}, {0, 1, 0}, 0.9f, 1.0f);
  const Region full = Region::full(96, 96);
  const FrameBuffer fb = look(room, cam);
  test::writePng("/tmp/tsr_vk_probe_own_centre.png", fb);
  const glm::vec2 right = test::project(cam, full, {0.8f + 0.354f, 0, 0.354f});
  const glm::vec4 r = fb.colour(int(right.x), int(right.y));
  EXPECT_GT(r.g, 0.8f) << "the green wall";
  EXPECT_LT(std::max(r.r, r.b), 0.1f) << "not the yellow ball in front of it from the room's centre";
}

// A yellow ball near the mirror, where its left side's reflection meets it
// (the view ray, from the camera 1.45 away, leaves that point towards
// (-0.97, 0, -0.24)): looked up in the direction of the red wall behind it
// (box-projected) the mirror would show red; followed along the ray
// through the probe's distances, it shows the ball.
TEST(VulkanReflectionProbe, MirrorShowsWhatStandsNearIt) {
  Room room;
  room.scene.addInstance(room.scene.addMesh(test::uvSphere(16, 32, 0.15f)), room.scene.addMaterial(glowing({1, 1, 0})),
                         glm::translate(glm::mat4(1.0f), glm::vec3(-0.1f, 0.0f, 0.22f)));
  const Camera cam = Camera::lookAt({0.8f, 0, 1.8f}, {0.8f, 0, 0}, {0, 1, 0}, 0.9f, 1.0f);
  const Region full = Region::full(96, 96);
  const FrameBuffer fb = look(room, cam);
  test::writePng("/tmp/tsr_vk_probe_near.png", fb);
  const glm::vec2 left = test::project(cam, full, {0.8f - 0.354f, 0, 0.354f});
  const glm::vec4 l = fb.colour(int(left.x), int(left.y));
  EXPECT_GT(std::min(l.r, l.g), 0.8f) << "the yellow ball";
  EXPECT_LT(l.b, 0.1f);
}

// A mirror ball on a floor lit from straight above, a roof over the floor's
// left half: the ball's lower left reflects the shadowed floor, its lower
// right the lit one. The probe's faces are drawn with the shadow maps.
TEST(VulkanReflectionProbe, MirrorShowsTheShadowsItFaces) {
  Scene scene(device());
  Material grey;
  grey.baseColor = glm::vec3(0.5f);
  const MaterialId g = scene.addMaterial(grey);
  scene.addInstance(scene.addMesh(test::groundQuad(0, 0, 3)), g, glm::mat4(1.0f));
  scene.addInstance(scene.addMesh(test::groundQuad(-1.5f, 0, 1.5f, 2.0f)), g, glm::mat4(1.0f));  // x in [-3, 0]
  const glm::vec3 centre(0.0f, 0.6f, 0.0f);
  scene.addInstance(scene.addMesh(test::uvSphere(32, 64, 0.5f)), scene.addMaterial(mirrorMaterial()),
                    glm::translate(glm::mat4(1.0f), centre));
  scene.addLight(DirectionalLight{{0, -1, 0}, glm::vec3(3.0f)});
  const Camera cam = Camera::lookAt({0, 0.8f, 3}, centre, {0, 1, 0}, 0.6f, 1.0f);
  const Region full = Region::full(96, 96);
  Renderer renderer(device(), {.shadows = true, .shadowMapSize = 512});
  FrameBuffer fb(96, 96);
  renderer.render(scene, cam, full, fb);
  test::writePng("/tmp/tsr_vk_probe_shadow.png", fb);
  auto seen = [&](float side) {
    const glm::vec3 n = glm::normalize(glm::vec3(0.6f * side, -0.5f, 0.62f)), p = centre + 0.5f * n;
    // Where the view ray, mirrored there, meets the floor: shadowed for side -1.
    const glm::vec3 v = glm::normalize(p - glm::vec3(0, 0.8f, 3)), r = glm::reflect(v, n);
    const glm::vec3 floor = p - r * (p.y / r.y);
    EXPECT_GT(side * floor.x, 0.2f);
    EXPECT_LT(std::abs(floor.z), 1.4f);
    const glm::vec2 px = test::project(cam, full, p);
    return fb.colour(int(px.x), int(px.y)).r;
  };
  const float shadowed = seen(-1.0f), lit = seen(1.0f);
  EXPECT_GT(lit, 0.1f);
  EXPECT_LT(shadowed, 0.3f * lit) << "the floor under the roof, reflected";
}

// A white metal of roughness 0.3 and one of 0.6 in the same room: both
// reflect the red wall to the left and the green one to the right (the
// probe, prefiltered), the rougher one mixing more of the other walls in.
TEST(VulkanReflectionProbe, RoughMetalShowsTheWallItFacesBlurred) {
  const Camera cam = Camera::lookAt({0.8f, 0, 1.8f}, {0.8f, 0, 0}, {0, 1, 0}, 0.9f, 1.0f);
  const Region full = Region::full(96, 96);
  const glm::vec2 left = test::project(cam, full, {0.8f - 0.354f, 0, 0.354f});
  const glm::vec2 right = test::project(cam, full, {0.8f + 0.354f, 0, 0.354f});
  auto purity = [](const glm::vec4& c, int channel) { return c[channel] / (c.r + c.g + c.b); };
  float previous[2] = {1.01f, 1.01f};  // a smooth metal reflects the wall alone
  for (float roughness : {0.0f, 0.3f, 0.6f}) {
    SCOPED_TRACE(roughness);
    Material metal;
    metal.type = MaterialType::MetallicRoughness;
    metal.baseColor = glm::vec3(1.0f);
    metal.metallic = 1.0f;
    metal.roughness = roughness;
    Room room(metal);
    Renderer renderer(device(), {.emitterLights = 0, .emitterAmbient = false});
    FrameBuffer fb(96, 96);
    renderer.render(room.scene, cam, full, fb);
    test::writePng("/tmp/tsr_vk_probe_rough_" + std::to_string(int(roughness * 10)) + ".png", fb);
    EXPECT_EQ(renderer.lastStats().probes, 1u);
    const glm::vec4 l = fb.colour(int(left.x), int(left.y)), r = fb.colour(int(right.x), int(right.y));
    EXPECT_GT(l.r, 2.0f * std::max(l.g, l.b)) << "mostly the red wall";
    EXPECT_GT(r.g, 2.0f * std::max(r.r, r.b)) << "mostly the green wall";
    EXPECT_LT(purity(l, 0), previous[0]) << "rougher: more of the other walls";
    EXPECT_LT(purity(r, 1), previous[1]);
    previous[0] = purity(l, 0);
    previous[1] = purity(r, 1);
    if (roughness == 0.3f) {  // an edit refilters, and the reflection follows it
      room.scene.setMaterial(room.red, glowing({1, 1, 0}));
      renderer.render(room.scene, cam, full, fb);
      EXPECT_EQ(renderer.lastStats().probes, 1u);
      const glm::vec4 edited = fb.colour(int(left.x), int(left.y));
      EXPECT_GT(edited.g, 0.5f * edited.r) << "the wall turned yellow";
    }
  }
}

// A glass ball is a lens: light refracted in at its left side leaves its
// far side bent farther right and finds the green wall, where refraction at
// the near side alone would still go on to the blue wall behind (worked
// out in the room's geometry for index 2: a ray meeting the ball 50 degrees
// left of its front leaves it heading (0.87, 0, -0.49)). Straight through
// the middle, the blue wall.
TEST(VulkanReflectionProbe, GlassBallRefractsInAndOut) {
  Material glass;
  glass.type = MaterialType::Glass;
  glass.baseColor = glm::vec3(1.0f);
  glass.ior = 2.0f;
  Room room(glass);
  const Camera cam = Camera::lookAt({0.8f, 0, 1.8f}, {0.8f, 0, 0}, {0, 1, 0}, 0.9f, 1.0f);
  const Region full = Region::full(96, 96);
  const FrameBuffer fb = look(room, cam);
  test::writePng("/tmp/tsr_vk_probe_glass.png", fb);
  const float a = glm::radians(50.0f);
  const glm::vec2 side = test::project(cam, full, {0.8f - 0.5f * std::sin(a), 0, 0.5f * std::cos(a)});
  const glm::vec4 s = fb.colour(int(side.x), int(side.y));
  EXPECT_GT(s.g, 2.0f * std::max(s.r, s.b)) << "the green wall, through both sides";
  const glm::vec2 centre = test::project(cam, full, {0.8f, 0, 0.5f});
  const glm::vec4 c = fb.colour(int(centre.x), int(centre.y));
  EXPECT_GT(c.b, 2.0f * std::max(c.r, c.g)) << "the blue wall, straight through";
}

// Rough glass resting on the floor touches the scene's bounds; it is still
// left out of the probe, or it would be drawn there (unlit by the probe it
// is drawing) and then seen, dark, through itself: from the probe's centre
// (the room's) the ball covers the blue wall behind it.
TEST(VulkanReflectionProbe, RoughGlassOnTheFloorIsNotSeenThroughItself) {
  Material frosted;
  frosted.type = MaterialType::Dielectric;
  frosted.baseColor = glm::vec3(1.0f);
  frosted.roughness = 0.2f;
  frosted.ior = 1.5f;
  Room room(frosted, {0.0f, -1.2f, -0.6f}, 0.8f);
  const Camera cam = Camera::lookAt({0.0f, -1.2f, 1.8f}, {0.0f, -1.2f, -0.6f}, {0, 1, 0}, 0.9f, 1.0f);
  const Region full = Region::full(96, 96);
  const FrameBuffer fb = look(room, cam);
  const glm::vec2 centre = test::project(cam, full, {0.0f, -1.2f, 0.2f});
  const glm::vec4 c = fb.colour(int(centre.x), int(centre.y));
  EXPECT_GT(c.b, 0.4f) << "the blue wall behind, through the ball";
  EXPECT_GT(c.b, std::max(c.r, c.g));
}

}  // namespace
}  // namespace tsr::vk
