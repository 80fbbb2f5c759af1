// The viewer's actions that scripts, keys and panels share: script steps,
// screenshots, picking, bookmarks.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <span>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "tsr/imageio/image_codec.hpp"
#include "tsr/med/coverage/ranking.hpp"
#include "tsr/med/file_replacement.hpp"
#include "tsr/med/image_file.hpp"
#include "tsr/vk/swapchain_target.hpp"
#include "viewer.hpp"

namespace tsr::app {

namespace {

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && std::equal(tail.rbegin(), tail.rend(), s.rbegin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) == b;
         });
}

}  // namespace

// One action a frame; waits hold the script where it is. False: the script
// is done and --exit-after asks to quit.
bool Viewer::runScript() {
  if (framesToWait_ > 0) {
    --framesToWait_;
    return true;
  }
  if (samplesToWait_ > 0) {
    bool done = true;
    // Path tracers rendered here; a cluster's renders whole frames.
    for (const auto& pane : panes_)
      if (registry_.capabilities(pane.backend()).progressive && pane.progressive() && pane.converging() &&
          pane.samples() < std::min<std::uint32_t>(std::uint32_t(samplesToWait_), convergence_.sampleLimit))
        done = false;
    // A pane that has not rendered yet counts as not there yet.
    for (const auto& pane : panes_)
      if (registry_.capabilities(pane.backend()).progressive &&
          (pane.shownBackend() != pane.backend() || (pane.progressive() && pane.samples() == 0)))
        done = false;
    if (convergence_.paused) done = true;  // paused: it would never come
    if (!done) return true;
    samplesToWait_ = 0;
  }
  if (scriptNext_ >= script_.size()) return !(options_.exitAfter && !script_.empty());
  const ScriptAction& action = script_[scriptNext_++];
  try {
    runAction(action);
  } catch (const std::exception& e) {
    // The script is the user's command: its failure ends the run like a bad command line.
    throw std::runtime_error(action.where + ": " + e.what());
  }
  return true;
}

void Viewer::runAction(const ScriptAction& a) {
  auto* camera = session_->source.find<sg::Camera>(session_->camera);
  if (a.verb == "backend") {
    panes_[a.viewport].setBackend(a.words[1]);
  } else if (a.verb == "orbit") {
    orbit_.orbit(float(a.number), 0.0f);
  } else if (a.verb == "tilt") {
    orbit_.orbit(0.0f, float(a.number));
  } else if (a.verb == "pan") {
    orbit_.pan(float(a.number), float(a.number2), camera->verticalFov());
  } else if (a.verb == "zoom") {
    orbit_.zoom(float(a.number));
  } else if (a.verb == "wait-frames") {
    framesToWait_ = a.count;
  } else if (a.verb == "wait-samples") {
    // A playing animation moves the scene every frame, so the samples start
    // again each frame: the wait would never end.
    bool refining = false;
    for (const auto& pane : panes_) refining |= registry_.capabilities(pane.backend()).progressive;
    if (playing_ && refining && !convergence_.paused)
      throw std::runtime_error("wait samples while the animation plays would never end: stop it with 'time SECONDS' "
                               "first");
    samplesToWait_ = a.count;
  } else if (a.verb == "param") {
    auto [name, value] = med::Parameters::parse(a.words[1]);
    panes_[a.viewport].setParameter(registry_, name, value);
  } else if (a.verb == "limit") {
    convergence_.sampleLimit = std::uint32_t(a.count);
  } else if (a.verb == "pause" || a.verb == "resume") {
    convergence_.paused = a.verb == "pause";
  } else if (a.verb == "raster-while-moving") {
    convergence_.rasterWhileMoving = a.count != 0;
  } else if (a.verb == "workload") {
    showWorkload_ = a.count != 0;
  } else if (a.verb == "time") {
    playing_ = false;
    setAnimationTime(a.number);
  } else if (a.verb == "lens") {
    camera->setApertureRadius(float(a.number));
    camera->setFocusDistance(float(a.number2));
  } else if (a.verb == "shutter") {
    setShutter(float(a.number), float(a.number2));
  } else if (a.verb == "focus-on") {
    focusOn(a.viewport, std::uint32_t(a.count), std::uint32_t(a.number2));
  } else if (a.verb == "pick") {
    pick(a.viewport, std::uint32_t(a.count), std::uint32_t(a.number2));
  } else if (a.verb == "bookmark") {
    if (a.words[0] == "save")
      saveBookmark(a.words[1]);
    else
      loadBookmark(a.words[1]);
  } else if (a.verb == "screenshot") {
    screenshotPane(a.viewport, a.words[0]);
  } else if (a.verb == "window-screenshot") {
    screenshotWindow(a.words[0]);
  } else if (a.verb == "open") {
    loadScene(a.words[0]);
  } else if (a.verb == "report") {
    report();
  }
}

// One line a viewport: how long ago and how many frames ago the camera
// moved, and what is shown now. After "orbit" and "wait samples 2" the
// seconds are the time to the first filtered preview; between two reports
// the frames over the seconds are the progressive frame rate.
void Viewer::report() const {
  const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - lastMove_).count();
  for (std::size_t i = 0; i < panes_.size(); ++i) {
    const ViewerPane& p = panes_[i];
    std::cout << "report: viewport " << i << ": " << since << " s and " << framesSinceMove_
              << " frames since the camera moved, showing " << p.shownBackend()
              << (p.showingWhitted() ? " (whitted)" : "") << ", " << p.samples() << " samples, " << p.samplesPerSecond()
              << " spp/s" << std::endl;
  }
}

void Viewer::screenshotPane(std::size_t pane, const std::string& path) {
  ViewerPane& p = panes_.at(pane);
  if (p.frame().width == 0)
    throw std::runtime_error("screenshot " + path + ": viewport " + std::to_string(pane) +
                             " has not rendered yet (wait frames 1 first)");
  if (endsWith(path, ".exr")) {
    const auto* camera = session_->replica.scene().find<sg::Camera>(session_->camera);
    const med::View view = med::View::fromCamera(*camera, p.frame().width, p.frame().height);
    med::writeLayeredExr(path, p.renderWithOutputs(registry_, *contexts_, session_->replica, view));
  } else {
    med::writeImage(path, p.frame());
  }
  status_ = "wrote " + path;
  std::cout << "wrote " << path << std::endl;
}

// The window as presented, panels included: the swapchain image read back.
void Viewer::screenshotWindow(const std::string& path) {
  const auto& bytes = target_->lastPresentedPixels();
  const std::uint32_t w = target_->lastPresentedWidth(), h = target_->lastPresentedHeight();
  if (bytes.empty() || w == 0) throw std::runtime_error("window-screenshot " + path + ": nothing presented yet");
  const bool bgra = target_->format() == VK_FORMAT_B8G8R8A8_SRGB || target_->format() == VK_FORMAT_B8G8R8A8_UNORM;
  std::vector<std::uint8_t> rgb(std::size_t(w) * h * 3);
  for (std::size_t i = 0; i < std::size_t(w) * h; ++i) {
    rgb[3 * i + 0] = bytes[4 * i + (bgra ? 2 : 0)];
    rgb[3 * i + 1] = bytes[4 * i + 1];
    rgb[3 * i + 2] = bytes[4 * i + (bgra ? 0 : 2)];
  }
  // The bytes are sRGB-encoded already: written as they are.
  imageio::Layout layout;
  layout.width = w, layout.height = h, layout.channels = 3;
  med::replaceFile(path, [&](const std::string& temporary) {
    imageio::writeFile(temporary, path, layout, std::as_bytes(std::span(rgb)));
  });
  status_ = "wrote " + path;
  std::cout << "wrote " << path << std::endl;
}

void Viewer::pick(std::size_t pane, std::uint32_t x, std::uint32_t y) {
  const med::FrameBuffer& fb = panes_.at(pane).frame();
  auto it = fb.outputs.find(med::kIdOutput);
  if (it == fb.outputs.end() || x >= fb.width || y >= fb.height) {
    selected_ = sg::kNoContainer;
    return;
  }
  const glm::vec4 id = it->second[fb.index(x, y)];
  selected_ = id.a > 0 ? med::decodeObjectId(id) : sg::kNoContainer;
  std::cout << "viewport " << pane << ": picked "
            << (selected_ == sg::kNoContainer ? std::string("nothing") : "object " + std::to_string(selected_))
            << std::endl;
}

// The depth the pane's last frame shows at (x, y) becomes the focus distance.
void Viewer::focusOn(std::size_t pane, std::uint32_t x, std::uint32_t y) {
  const med::FrameBuffer& fb = panes_.at(pane).frame();
  const float depth = x < fb.width && y < fb.height && !fb.depth.empty() ? fb.depth[fb.index(x, y)] : INFINITY;
  if (!(std::isfinite(depth) && depth > 0.0f)) {
    status_ = "nothing to focus on there (the background)";
    std::cout << "viewport " << pane << ": " << status_ << std::endl;
    return;
  }
  session_->source.find<sg::Camera>(session_->camera)->setFocusDistance(depth);
  status_ = "focused at " + std::to_string(depth);
  std::cout << "viewport " << pane << ": focus distance " << depth << std::endl;
}

void Viewer::saveBookmark(const std::string& name) {
  Bookmark b;
  b.name = name;
  b.target = orbit_.target();
  b.distance = orbit_.distance();
  b.yaw = orbit_.yawDegrees();
  b.pitch = orbit_.pitchDegrees();
  bookmarks_.save(b);
  bookmarkMessage_ = "saved '" + name + "' to " + bookmarks_.path;
}

void Viewer::loadBookmark(const std::string& name) {
  const Bookmark* b = bookmarks_.find(name);
  if (!b) throw std::runtime_error("no bookmark '" + name + "' in " + bookmarks_.path);
  orbit_.set(b->target, b->distance, b->yaw, b->pitch);
}

}  // namespace tsr::app
