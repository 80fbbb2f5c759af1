#include "quality_scene.hpp"

#include <chrono>
#include <cmath>
#include <cstring>
#include <deque>
#include <stdexcept>

#include "tsr/med/view.hpp"
#include "tsr/med/viewport.hpp"
#include "tsr/sg/camera.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include "tsr/med/image_file.hpp"
#include "tsr/sg/background.hpp"
#include "tsr/sg/image.hpp"
#include "tsr/sg/import/default_light_rig.hpp"
#include "tsr/sg/import/scene_camera.hpp"
#include "tsr/sg/light.hpp"
#include "tsr/sg/node_world.hpp"
#include "tsr/sg/surface_material.hpp"

namespace tsr::quality {

namespace {

// make_cornell.py gives the right wall the only pure red material.
void makeRedWallGlossy(sg::Scene& scene) {
  for (auto id : scene.ids()) {
    auto* m = scene.find<sg::SurfaceMaterial>(id);
    if (!m) continue;
    const sg::Vec3 c = m->baseColor();
    if (c.r > 0.9f && c.g < 0.1f && c.b < 0.1f) {
      m->setBaseColor({0.9f, 0.9f, 0.9f});
      m->setMetallic(1.0f);
      m->setRoughness(0.2f);
      return;
    }
  }
  throw std::runtime_error("glossy variant: the scene has no red surface material to make glossy");
}

// The file's pixels as a linear float image behind an environment background.
void lightByEnvironment(sg::Scene& scene, sg::ContainerId& background, const std::string& path) {
  const med::FrameBuffer map = med::readImage(path);
  std::vector<std::uint8_t> bytes(map.colour.size() * 4 * sizeof(float));
  std::memcpy(bytes.data(), map.colour.data(), bytes.size());
  auto& image = scene.create<sg::Image>(path);
  image.setPixels(map.width, map.height, 4, sg::PixelFormat::Float32, std::move(bytes));
  image.setColorSpace(sg::ColorSpace::Linear);
  auto* bg = scene.find<sg::Background>(background);
  if (!bg) {
    bg = &scene.create<sg::Background>("environment");
    background = bg->id();
  }
  bg->setKind(sg::BackgroundKind::Environment);
  bg->setEnvironment(image.id());
  bg->setIntensity(1.0f);
}

}  // namespace

QualityScene::QualityScene(std::string key, std::string label, const std::string& source, bool glossy,
                           const med::ViewportRegistry& registry, const std::string& environment, const Motion& motion)
    : key_(std::move(key)), label_(std::move(label)), registry_(registry), motion_(motion) {
  imported_ = sg::importScene(source_, source);
  camera_ = imported_.cameras.empty() ? sg::addFramingCamera(source_, imported_.root) : imported_.cameras.front();
  if (glossy) makeRedWallGlossy(source_);
  if (!environment.empty()) lightByEnvironment(source_, imported_.background, environment);
  if (!sg::hasOwnLighting(source_, imported_.root, imported_.background)) {
    const sg::DefaultLightRig rig = sg::addDefaultLightRig(source_, imported_.root, imported_.background);
    sg::followCamera(source_, rig, sg::cameraWorldPose(source_, camera_));
  }
  if (motion_.moves()) {
    auto* camera = source_.find<sg::Camera>(camera_);
    camera->setShutterOpen(motion_.shutterOpen);
    camera->setShutterClose(motion_.shutterClose);
    poseAnimations(motion_.time);
  }
  replica_.apply(source_.commit());
  med::Parameters p;
  p.set("spp", std::int64_t{1});
  anchor_ = viewport(p);
  render(*anchor_, 8);  // converts the scene once for all later viewports
}

std::unique_ptr<med::Viewport> QualityScene::viewport(const med::Parameters& parameters) {
  med::ViewportSettings s;
  s.backend = "embree";
  s.root = imported_.root;
  s.background = imported_.background;
  s.parameters = parameters;
  return registry_.create(s, contexts_);
}

void QualityScene::poseAnimations(float seconds) {
  const float dt = motion_.moves() ? motion_.frameInterval : 0.0f;
  for (const auto& animation : imported_.animations) animation.apply(source_, seconds, dt);
}

void QualityScene::pose(float seconds, float lightScale, float pan) {
  if (lightIntensities_.empty())
    for (auto id : source_.ids())
      if (const auto* light = source_.find<sg::Light>(id)) lightIntensities_.emplace_back(id, light->intensity());
  poseAnimations(seconds);
  for (const auto& [id, intensity] : lightIntensities_)
    source_.find<sg::Light>(id)->setIntensity(intensity * lightScale);
  auto* camera = source_.find<sg::Camera>(camera_);
  if (!cameraPose_) cameraPose_ = camera->pose();
  if (pan != 0.0f || camera->pose() != *cameraPose_)
    camera->setPose(*cameraPose_ * glm::translate(glm::mat4(1.0f), glm::vec3(pan, 0.0f, 0.0f)));
  lastCommit_ = source_.commit();
  replica_.apply(lastCommit_);
}

std::vector<Shot> QualityScene::renderAhead(med::Viewport& viewport, std::uint32_t size, int frames,
                                            const std::function<void(int)>& pose,
                                            const std::vector<std::string>& outputs) {
  const int lookahead = static_cast<int>(viewport.lookahead());
  sg::Replica ahead, shown;
  const auto start = source_.snapshot();
  ahead.apply(start);
  shown.apply(start);
  std::deque<sg::ChangeListPtr> pending;
  std::vector<Shot> shots;
  double preparing = 0;
  for (int posed = 0; posed < frames + lookahead; ++posed) {
    if (posed < frames) {
      pose(posed);  // commits into replica_; the same list goes to both replicas here
      pending.push_back(lastCommit_);
      ahead.apply(lastCommit_);
      const auto t = std::chrono::steady_clock::now();
      viewport.prepare(ahead, posed);
      preparing += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    }
    const int frame = posed - lookahead;
    if (frame < 0) continue;
    shown.apply(pending.front());
    pending.pop_front();
    const auto view = med::View::fromCamera(*shown.scene().find<sg::Camera>(camera_), size, size);
    med::RenderControl control;
    control.outputs = outputs;
    control.frame = frame;
    Shot shot;
    const auto stats = viewport.render(shown, view, shot.image, control);
    shot.seconds = stats.seconds - stats.syncSeconds;
    shot.samples = stats.samples;
    shots.push_back(std::move(shot));
  }
  for (auto& shot : shots) shot.seconds += preparing / double(shots.size());
  return shots;
}

Shot QualityScene::render(med::Viewport& viewport, std::uint32_t size, bool wantBlend,
                          const std::vector<std::string>& outputs) {
  return renderSized(viewport, size, size, outputs, wantBlend);
}

void QualityScene::orbit(float degrees, float pivotDistance) {
  auto* camera = source_.find<sg::Camera>(camera_);
  if (!cameraPose_) cameraPose_ = camera->pose();
  const glm::mat4& pose = *cameraPose_;
  const glm::vec3 pivot = glm::vec3(pose[3]) - glm::normalize(glm::vec3(pose[2])) * pivotDistance;
  const glm::mat4 turn = glm::translate(glm::mat4(1.0f), pivot) *
                         glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(0, 1, 0)) *
                         glm::translate(glm::mat4(1.0f), -pivot);
  camera->setPose(turn * pose);
  lastCommit_ = source_.commit();
  replica_.apply(lastCommit_);
}

Shot QualityScene::renderSized(med::Viewport& viewport, std::uint32_t width, std::uint32_t height,
                               const std::vector<std::string>& outputs, bool wantBlend) {
  const auto view = med::View::fromCamera(*replica_.scene().find<sg::Camera>(camera_), width, height);
  med::RenderControl control;
  control.outputs = outputs;
  if (wantBlend) control.outputs->push_back("blend");
  Shot shot;
  const auto stats = viewport.render(replica_, view, shot.image, control);
  shot.seconds = stats.seconds - stats.syncSeconds;
  shot.totalSeconds = stats.seconds;
  shot.samples = stats.samples;
  return shot;
}

}  // namespace tsr::quality
