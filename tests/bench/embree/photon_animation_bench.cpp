// Photons vs frame-by-frame path tracing on small animated scenes: relMSE
// against a high-spp reference per frame, and flicker (tRelMSE of the
// indirect part). Prints a table; not a unit test.
//   photon_animation_bench [--frames N] [--size S] [--spp K] [--ref-spp R] [--photons P]
#include "test_scenes.hpp"

#include "tsr/embree/photon_sequence.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

using namespace tsr::embree;

namespace {

struct Options {
  int frames = 12;
  std::uint32_t size = 64;
  std::uint32_t spp = 16;
  std::uint32_t refSpp = 1024;
  std::uint32_t photons = 0;  // 0: from the pilot pass
};

using Image = std::vector<glm::vec3>;
struct Frames {
  std::vector<Image> beauty, indirect;
  double seconds = 0.0;
  double photonSeconds = 0.0, reconstructSeconds = 0.0;  // parts of seconds (photon method)
};

Image channel(const FrameBuffer& fb, Channel c) {
  Image out;
  for (std::uint32_t y = 0; y < fb.height(); ++y)
    for (std::uint32_t x = 0; x < fb.width(); ++x) out.push_back(fb.mean(c, x, y));
  return out;
}

double relMse(const Image& a, const Image& ref) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double d = luminance(a[i]) - luminance(ref[i]), y = luminance(ref[i]);
    s += d * d / (y * y + 0.01);
  }
  return s / double(a.size());
}

double meanRelMse(const std::vector<Image>& a, const std::vector<Image>& ref) {
  double s = 0.0;
  for (std::size_t t = 0; t < a.size(); ++t) s += relMse(a[t], ref[t]);
  return s / double(a.size());
}

// mean over pixels of ((a_t - a_{t-1}) - (y_t - y_{t-1}))^2 / (y_t^2 + 0.01), averaged over t
double tRelMse(const std::vector<Image>& a, const std::vector<Image>& ref) {
  double s = 0.0;
  for (std::size_t t = 1; t < a.size(); ++t) {
    double f = 0.0;
    for (std::size_t i = 0; i < a[t].size(); ++i) {
      const double y = luminance(ref[t][i]);
      const double d = (luminance(a[t][i]) - luminance(a[t - 1][i])) - (y - luminance(ref[t - 1][i]));
      f += d * d / (y * y + 0.01);
    }
    s += f / double(a[t].size());
  }
  return a.size() > 1 ? s / double(a.size() - 1) : 0.0;
}

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct AnimatedScene {
  std::string name;
  Scene scene{test::sharedDevice()};
  Camera camera;
  std::function<void(Scene&, int)> pose;
};

Frames pathTraced(AnimatedScene& s, const Options& o, std::uint32_t spp, std::uint64_t seed) {
  Frames out;
  RenderSettings rs;
  rs.samplesPerPass = spp;
  rs.seed = seed;
  Renderer r(rs);
  const Region region = Region::full(o.size, o.size);
  const auto t0 = std::chrono::steady_clock::now();
  for (int f = 0; f < o.frames; ++f) {
    s.pose(s.scene, f);
    FrameBuffer fb(o.size, o.size);
    r.renderPass(s.scene, s.camera, region, fb);
    out.beauty.push_back(channel(fb, Channel::Colour));
    out.indirect.push_back(channel(fb, Channel::Indirect));
  }
  out.seconds = since(t0);
  return out;
}

Frames photons(AnimatedScene& s, const Options& o, std::uint32_t* perFrame) {
  Frames out;
  RenderSettings rs;
  rs.samplesPerPass = o.spp;
  Renderer r(rs);
  PhotonSettings ps;
  ps.photonsPerFrame = o.photons;
  const Region region = Region::full(o.size, o.size);
  const auto t0 = std::chrono::steady_clock::now();
  PhotonSequence seq(ps);
  const int ahead = int(seq.lookahead());
  for (int f = 0; f < o.frames + ahead; ++f) {
    if (f < o.frames) {
      const auto tp = std::chrono::steady_clock::now();
      s.pose(s.scene, f);
      seq.addFrame(s.scene, f);
      out.photonSeconds += since(tp);
    }
    const int g = f - ahead;
    if (g < 0) continue;
    const auto tr = std::chrono::steady_clock::now();
    const IrradianceField field = seq.reconstruct(g).field;
    out.reconstructSeconds += since(tr);
    s.pose(s.scene, g);
    FrameBuffer fb(o.size, o.size);
    r.renderWithIrradiance(s.scene, s.camera, region, fb, field);
    out.beauty.push_back(channel(fb, Channel::Colour));
    out.indirect.push_back(channel(fb, Channel::Indirect));
  }
  out.seconds = since(t0);
  *perFrame = seq.photonsPerFrame();
  return out;
}

void movingLight(AnimatedScene& s, int frames) {
  s.name = "moving light";
  s.camera = test::cornellBox(s.scene, 0);
  s.pose = [frames](Scene& scene, int f) {
    const float x = 130.0f + 300.0f * float(f) / float(std::max(1, frames - 1));
    scene.setLight(LightId{0}, PointLight{{x, 400.0f, 280.0f}, glm::vec3(100000.0f)});
  };
}

void movingObject(AnimatedScene& s, int frames) {
  s.name = "moving ball";
  s.camera = test::cornellBox(s.scene, 0);
  Material m;
  m.baseColor = glm::vec3(0.2f, 0.4f, 0.8f);
  MeshData ball = test::uvSphere({0.0f, 0.0f, 0.0f}, 60.0f, 400, true);
  ball.usage = MeshUsage::Animated;
  const InstanceId id = s.scene.addInstance(s.scene.addMesh(std::move(ball)), s.scene.addMaterial(m), glm::mat4(1.0f));
  s.pose = [frames, id](Scene& scene, int f) {
    const float x = 120.0f + 320.0f * float(f) / float(std::max(1, frames - 1));
    scene.setInstanceTransform(id, glm::translate(glm::mat4(1.0f), glm::vec3(x, 60.0f, 120.0f)));
  };
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i];
    const long v = std::strtol(argv[i + 1], nullptr, 10);
    if (v <= 0 || v > 1 << 24) {
      std::fprintf(stderr, "%s needs a positive number\n", k.c_str());
      return 2;
    }
    if (k == "--frames")
      o.frames = int(v);
    else if (k == "--size")
      o.size = std::uint32_t(v);
    else if (k == "--spp")
      o.spp = std::uint32_t(v);
    else if (k == "--ref-spp")
      o.refSpp = std::uint32_t(v);
    else if (k == "--photons")
      o.photons = std::uint32_t(v);
    else {
      std::fprintf(stderr, "unknown option %s\n", k.c_str());
      return 2;
    }
  }
  std::printf("%d frames, %ux%u, %u spp (direct and frame-by-frame), reference %u spp\n", o.frames, o.size, o.size,
              o.spp, o.refSpp);
  std::printf("%-13s %-22s %9s %12s %12s %14s\n", "scene", "method", "time s", "relMSE", "relMSE ind", "tRelMSE ind");
  for (auto build : {movingLight, movingObject}) {
    AnimatedScene s;
    build(s, o.frames);
    const Frames ref = pathTraced(s, o, o.refSpp, 99);
    const Frames pt = pathTraced(s, o, o.spp, 1);
    std::uint32_t perFrame = 0;
    const Frames ph = photons(s, o, &perFrame);
    auto row = [&](const std::string& method, const Frames& f) {
      std::printf("%-13s %-22s %9.2f %12.5f %12.5f %14.6f\n", s.name.c_str(), method.c_str(), f.seconds,
                  meanRelMse(f.beauty, ref.beauty), meanRelMse(f.indirect, ref.indirect),
                  tRelMse(f.indirect, ref.indirect));
    };
    row("path tracing " + std::to_string(o.spp) + " spp", pt);
    row("photons " + std::to_string(perFrame) + "/frame", ph);
    std::printf("%-13s %-22s %9.2f photon passes (pilot included), %.2f reconstruction\n", s.name.c_str(), "",
                ph.photonSeconds, ph.reconstructSeconds);
    std::printf("%-13s %-22s %9.2f\n", s.name.c_str(), "reference", ref.seconds);
  }
  return 0;
}
