// mode=whitted, the middle renderer of figure 5.6, through the real Embree
// viewport: one sample per pixel, a mirror sphere that shows the two-coloured
// wall it faces without blending its halves, hard shadows of a point light,
// tiles that are crops, and a malformed mode refused with a message that
// names the choices.
#include <gtest/gtest.h>

#include <algorithm>

#include "../vulkan/test_scenes.hpp"
#include "tsr/med/embree/register.hpp"

using namespace tsr;

namespace {

constexpr std::uint32_t kSize = 96;
const sg::Vec3 kEye(0.0f, 1.6f, 5.0f);
// Albedos that name the surfaces in the albedo output.
const sg::Vec3 kMirrorColour(0.95f, 0.95f, 0.95f);
const sg::Vec3 kFloorColour(0.7f, 0.7f, 0.7f);

// A floor under a point light, a quad above it casting a shadow, a mirror
// sphere, and behind the camera a wall whose left half is green and right
// half blue: the sphere faces it and is the only way the camera sees it.
struct WhittedRig {
  sg::Scene source;
  sg::ContainerId root = sg::kNoContainer, camera = sg::kNoContainer;
  sg::Replica replica;
  med::ViewportRegistry registry;
  med::ContextPool contexts;

  WhittedRig() {
    auto& group = source.create<sg::Group>("root");
    root = group.id();
    auto material = [&](const char* name, sg::Vec3 c, float metallic, float roughness) {
      auto& m = source.create<sg::SurfaceMaterial>(name);
      m.setBaseColor(c);
      m.setMetallic(metallic);
      m.setRoughness(roughness);
      return m.id();
    };
    const auto floor = material("floor", kFloorColour, 0.0f, 1.0f);
    test::addQuad(source, root, "floor", {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}, {-4, 0, -4}, floor);
    test::addQuad(source, root, "occluder", {-1.8f, 1.2f, 0.5f}, {-0.8f, 1.2f, 0.5f}, {-0.8f, 1.2f, -0.5f},
                  {-1.8f, 1.2f, -0.5f}, material("occluder", {0.5f, 0.5f, 0.5f}, 0.0f, 1.0f));
    test::addSphere(source, root, "mirror", {0.9f, 0.8f, 0.0f}, 0.8f, 64,
                    material("mirror", kMirrorColour, 1.0f, 0.0f));
    test::addQuad(source, root, "green half", {0, 0, 8}, {-8, 0, 8}, {-8, 6, 8}, {0, 6, 8},
                  material("green", {0.1f, 0.8f, 0.1f}, 0.0f, 1.0f));
    test::addQuad(source, root, "blue half", {8, 0, 8}, {0, 0, 8}, {0, 6, 8}, {8, 6, 8},
                  material("blue", {0.1f, 0.1f, 0.8f}, 0.0f, 1.0f));
    auto& light = source.create<sg::Light>("point light");
    light.setKind(sg::LightKind::Point);
    light.setPosition({-1.0f, 4.0f, 3.0f});
    light.setIntensity(40.0f);
    group.addChild(light.id());
    auto& cam = source.create<sg::Camera>("camera");
    cam.lookAt(kEye, {0.3f, 0.6f, 0.0f});
    camera = cam.id();
    replica.apply(source.commit());
    med::registerEmbree(registry);
  }
  med::ViewportSettings settings(const std::string& mode = "whitted") const {
    med::ViewportSettings s;
    s.backend = "embree";
    s.root = root;
    s.parameters.set("mode", mode);
    s.parameters.set("spp", std::int64_t{16});  // ignored by mode=whitted: one sample is the image
    return s;
  }
  med::View view() const { return med::View::fromCamera(*replica.scene().find<sg::Camera>(camera), kSize, kSize); }
};

bool near(const glm::vec4& a, const sg::Vec3& b) {
  return std::abs(a.x - b.x) < 1e-4f && std::abs(a.y - b.y) < 1e-4f && std::abs(a.z - b.z) < 1e-4f;
}

}  // namespace

TEST(WhittedViewport, OneSampleMirrorShowsTheWallSharplyAndShadowsAreHard) {
  WhittedRig rig;
  auto viewport = rig.registry.create(rig.settings(), rig.contexts);
  med::FrameBuffer image;
  med::RenderControl control;
  control.outputs = std::vector<std::string>{"albedo"};
  const med::RenderStats stats = viewport->render(rig.replica, rig.view(), image, control);
  EXPECT_EQ(stats.samples, 1u) << "one sample per pixel, whatever spp says";
  EXPECT_GT(stats.rays, std::uint64_t{kSize} * kSize);
  test::keepImage("whitted", image);
  const auto& albedo = image.outputs.at("albedo");

  // The mirror shows the wall behind the camera, both halves, and no pixel
  // blends them: the reflection is as sharp as the pixel grid.
  std::size_t green = 0, blue = 0, blended = 0;
  // The floor is lit by the point light or in a shadow that is black: no
  // indirect light fills it and there is no penumbra to blend the two.
  std::size_t lit = 0, shadowed = 0, penumbra = 0;
  float brightestFloor = 0.0f;
  for (std::size_t i = 0; i < image.colour.size(); ++i) {
    const glm::vec4 c = image.colour[i];
    if (near(albedo[i], kFloorColour)) brightestFloor = std::max(brightestFloor, c.x);
  }
  ASSERT_GT(brightestFloor, 0.05f);
  for (std::size_t i = 0; i < image.colour.size(); ++i) {
    const glm::vec4 c = image.colour[i];
    if (near(albedo[i], kMirrorColour) && std::max(c.y, c.z) > 3.0f * c.x) {
      const float share = c.y / (c.y + c.z);
      green += share > 0.85f;
      blue += share < 0.15f;
      blended += share >= 0.15f && share <= 0.85f;
    }
    if (near(albedo[i], kFloorColour)) {
      shadowed += c.x == 0.0f && c.y == 0.0f && c.z == 0.0f;
      lit += c.x > 0.05f * brightestFloor;
      penumbra += c.x > 0.0f && c.x <= 0.05f * brightestFloor;
    }
  }
  EXPECT_GT(green, 20u) << "the wall's green half in the mirror";
  EXPECT_GT(blue, 20u) << "the wall's blue half in the mirror";
  EXPECT_EQ(blended, 0u) << "mirror pixels that mix the halves";
  EXPECT_GT(shadowed, 50u) << "floor pixels in the occluder's and sphere's shadows";
  EXPECT_GT(lit, 500u);
  EXPECT_EQ(penumbra, 0u) << "floor pixels between shadow and light";

  // Rendered again for the same view: the image stands, nothing is traced.
  med::FrameBuffer again;
  const med::RenderStats second = viewport->render(rig.replica, rig.view(), again, control);
  EXPECT_EQ(second.rays, 0u);
  EXPECT_EQ(again.colour, image.colour);

  // The path tracer of the same scene fills the shadows with indirect light.
  auto path = rig.registry.create(rig.settings("path"), rig.contexts);
  med::FrameBuffer traced;
  path->render(rig.replica, rig.view(), traced, control);
  std::size_t filled = 0;
  for (std::size_t i = 0; i < image.colour.size(); ++i)
    filled += near(albedo[i], kFloorColour) && image.colour[i].x == 0.0f && traced.colour[i].x > 0.0f;
  EXPECT_GT(filled, shadowed / 2);
}

TEST(WhittedViewport, TilesAreCropsAndThreadsDoNotMatter) {
  WhittedRig rig;
  med::FrameBuffer whole, tile;
  rig.registry.create(rig.settings(), rig.contexts)->render(rig.replica, rig.view(), whole);
  auto tiled = rig.registry.create(rig.settings(), rig.contexts);
  tiled->setParameter("threads", std::int64_t{1});
  const med::PixelRect rect{10, 20, 50, 61};
  tiled->render(rig.replica, rig.view().cropped(rect), tile);
  ASSERT_EQ(tile.width, rect.width());
  ASSERT_EQ(tile.height, rect.height());
  for (std::uint32_t y = 0; y < tile.height; ++y)
    for (std::uint32_t x = 0; x < tile.width; ++x)
      ASSERT_EQ(tile.colour[tile.index(x, y)], whole.colour[whole.index(rect.x0 + x, rect.y0 + y)])
          << "pixel " << x << "," << y;
}

TEST(WhittedViewport, AMalformedModeIsRefusedNamingTheChoices) {
  WhittedRig rig;
  auto settings = rig.settings("whited");
  try {
    rig.registry.create(settings, rig.contexts);
    FAIL() << "mode=whited was accepted";
  } catch (const med::ParameterError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("mode"), std::string::npos) << message;
    EXPECT_NE(message.find("whitted"), std::string::npos) << message;
    EXPECT_NE(message.find("path"), std::string::npos) << message;
  }
  settings.parameters.set("mode", std::int64_t{1});
  EXPECT_THROW(rig.registry.create(settings, rig.contexts), med::BadParameterValue);
  auto viewport = rig.registry.create(rig.settings("path"), rig.contexts);
  EXPECT_THROW(viewport->setParameter("mode", std::string("")), med::BadParameterValue);
}

// Figure 5.6's chain shows the Whitted image while the camera rests and
// goes back to the path tracer: the path tracer's samples outlive the
// Whitted frame (its own image, not the accumulation buffer), and a second
// Whitted frame of the same view traces nothing.
TEST(WhittedViewport, TheWhittedFrameLeavesThePathTracersSamplesAlone) {
  WhittedRig rig;
  auto viewport = rig.registry.create(rig.settings("path"), rig.contexts);
  viewport->setParameter("spp", std::int64_t{4});
  med::FrameBuffer path, whitted, again;
  const med::RenderStats first = viewport->render(rig.replica, rig.view(), path);
  ASSERT_EQ(first.samples, 4u);
  viewport->setParameter("mode", std::string("whitted"));
  EXPECT_GT(viewport->render(rig.replica, rig.view(), whitted).rays, 0u);
  EXPECT_EQ(viewport->render(rig.replica, rig.view(), whitted).rays, 0u) << "the same view again is free";
  viewport->setParameter("mode", std::string("path"));
  const med::RenderStats back = viewport->render(rig.replica, rig.view(), again);
  EXPECT_EQ(back.samples, 4u);
  EXPECT_EQ(back.rays, 0u) << "the four samples were kept";
  EXPECT_EQ(again.colour, path.colour);
}
