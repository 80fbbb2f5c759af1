// tessera-node --present window on a real X server (Xvfb): each node's
// window sits where the config places its screen and shows that screen's
// pixels of the local render. The pixels are read back from the server's
// own framebuffer, which Xvfb -fbdir keeps as an XWD file, so the test sees
// what a person at the wall would see. Run through xvfb-run by CTest
// (WallWindow.xvfb), which passes the folder as TSR_XVFB_FBDIR.
#include <cmath>
#include <optional>
#include <thread>

#include "wall/wall_test_util.hpp"

namespace tsr::cluster::test {
namespace {

using namespace std::chrono_literals;

// The X screen as 8-bit RGB, from the XWD dump Xvfb maps to its framebuffer.
struct XScreen {
  std::uint32_t width = 0, height = 0;
  std::vector<std::array<std::uint8_t, 3>> rgb;
  const std::array<std::uint8_t, 3>& at(std::uint32_t x, std::uint32_t y) const {
    return rgb[std::size_t{y} * width + x];
  }
};

std::optional<XScreen> readXvfbScreen(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), {}};
  if (bytes.size() < 100) return std::nullopt;
  // The header: 25 big-endian 32-bit fields (X11's XWDFileHeader).
  auto field = [&](int i) {
    const std::uint8_t* p = bytes.data() + 4 * i;
    return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3];
  };
  const std::uint32_t headerSize = field(0), width = field(4), height = field(5), byteOrder = field(7),
                      bitsPerPixel = field(11), bytesPerLine = field(12), redMask = field(14), greenMask = field(15),
                      blueMask = field(16), colours = field(19);
  if (bitsPerPixel != 32) throw std::runtime_error("Xvfb screen is not 32 bits per pixel (run it with depth 24)");
  const std::size_t pixels = headerSize + std::size_t{colours} * 12;  // XWDColor: 12 bytes each
  if (bytes.size() < pixels + std::size_t{bytesPerLine} * height) return std::nullopt;
  auto channel = [](std::uint32_t value, std::uint32_t mask) {
    int shift = 0;
    while (mask && !(mask & 1u)) {
      mask >>= 1;
      ++shift;
    }
    return static_cast<std::uint8_t>((value >> shift) & 0xffu);
  };
  XScreen s;
  s.width = width;
  s.height = height;
  s.rgb.resize(std::size_t{width} * height);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      const std::uint8_t* p = bytes.data() + pixels + std::size_t{y} * bytesPerLine + 4 * x;
      std::uint32_t v = byteOrder == 0
                            ? (std::uint32_t{p[3]} << 24 | std::uint32_t{p[2]} << 16 | std::uint32_t{p[1]} << 8 | p[0])
                            : (std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3]);
      s.rgb[std::size_t{y} * width + x] = {channel(v, redMask), channel(v, greenMask), channel(v, blueMask)};
    }
  return s;
}

// What a swapchain shows for linear colour: clamped, sRGB-encoded, 8 bits.
int srgb8(float linear) {
  float c = std::clamp(linear, 0.0f, 1.0f);
  float s = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
  return static_cast<int>(std::lround(s * 255.0f));
}

// Pixels of `region` of `ref` that the screen does not show at `origin` (±1 for rounding).
std::size_t mismatches(const XScreen& screen, std::uint32_t originX, std::uint32_t originY, const med::FrameBuffer& ref,
                       const med::PixelRect& region, std::string& first) {
  std::size_t bad = 0;
  for (std::uint32_t y = region.y0; y < region.y1; ++y)
    for (std::uint32_t x = region.x0; x < region.x1; ++x) {
      std::uint32_t sx = originX + x - region.x0, sy = originY + y - region.y0;
      if (sx >= screen.width || sy >= screen.height) {
        ++bad;
        continue;
      }
      const glm::vec4& c = ref.colour[ref.index(x, y)];
      const auto& shown = screen.at(sx, sy);
      int want[3] = {srgb8(c.r), srgb8(c.g), srgb8(c.b)};
      for (int k = 0; k < 3; ++k)
        if (std::abs(int{shown[k]} - want[k]) > 1) {
          if (bad == 0)
            first = "at " + std::to_string(x) + "," + std::to_string(y) + ": shown " + std::to_string(shown[0]) + "," +
                    std::to_string(shown[1]) + "," + std::to_string(shown[2]) + ", want " + std::to_string(want[0]) +
                    "," + std::to_string(want[1]) + "," + std::to_string(want[2]);
          ++bad;
          break;
        }
    }
  return bad;
}

TEST(WallWindow, EachNodeShowsItsScreenWhereTheConfigPlacesIt) {
  const char* display = std::getenv("DISPLAY");
  const char* fbdir = std::getenv("TSR_XVFB_FBDIR");
  if (!display || !fbdir) {
    if (std::getenv("TSR_REQUIRE_DISPLAY")) FAIL() << "no DISPLAY or TSR_XVFB_FBDIR: is xvfb-run broken?";
    GTEST_SKIP() << "needs Xvfb with -fbdir (run as WallWindow.xvfb)";
  }
  TempDir dir;
  Wall wall(dir.path, 2, /*windows=*/true);
  // Two screens side by side in a 160x96 frame; the right one has 4 pixels
  // of mullion. Their windows are placed apart on the X screen.
  std::string json = std::string(R"({"mode": "tiled", "backend": "embree", )") + kParameters + R"(, "nodes": [
      {"address": "127.0.0.1:1"}, {"address": "127.0.0.1:1"}],
    "wall": {"frame": [160, 96], "screens": [
      {"rect": [0, 0, 80, 96], "window": {"position": [8, 16]}},
      {"rect": [80, 0, 80, 96], "bezel": 4, "window": {"position": [200, 40]}}]}})";
  fs::path config = dir.path / "windows.json";
  std::ofstream(config) << json;
  fs::path log = dir.path / "wall.log";
  ASSERT_EQ(runWall(config.string() + " builtin:animated --nodes " + wall.addresses() + " --frames 3", log), 0)
      << slurp(log);

  // The last frame (pose 2/24 s) stays on the windows after the wall stops.
  const med::FrameBuffer ref = localFrame(2, 160, 96);
  const med::PixelRect left{0, 0, 80, 96}, right{84, 4, 156, 92};
  std::size_t badLeft = 0, badRight = 0;
  std::string firstLeft, firstRight;
  for (int attempt = 0; attempt < 100; ++attempt) {  // the window thread presents asynchronously
    std::optional<XScreen> screen = readXvfbScreen(fs::path(fbdir) / "Xvfb_screen0");
    ASSERT_TRUE(screen) << "cannot read " << fbdir << "/Xvfb_screen0";
    badLeft = mismatches(*screen, 8, 16, ref, left, firstLeft);
    badRight = mismatches(*screen, 200, 40, ref, right, firstRight);
    if (badLeft == 0 && badRight == 0) break;
    std::this_thread::sleep_for(100ms);
  }
  EXPECT_EQ(badLeft, 0u) << "node 0's window at 8,16: " << firstLeft;
  EXPECT_EQ(badRight, 0u) << "node 1's window at 200,40: " << firstRight;
}

}  // namespace
}  // namespace tsr::cluster::test
