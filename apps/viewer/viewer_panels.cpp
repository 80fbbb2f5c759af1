// The viewer's ImGui panels: scene and camera, one panel per viewport (its
// back-end, and for the path tracer its convergence and filter controls;
// for coverage the ranked list), animation.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include <imgui.h>

#include "tsr/cluster/cluster_window.hpp"
#include "tsr/med/coverage/ranking.hpp"
#include "viewer.hpp"

namespace tsr::app {

namespace {

// One control per parameter the back-end declares, from its table: a
// checkbox, an integer or real field clamped to the range, or a combo.
// Returns the edited parameter, if any.
std::optional<std::pair<std::string, med::ParameterValue>> parameterControl(const med::ParameterTable& table,
                                                                            const med::ParameterSpec& spec,
                                                                            const med::Parameters& p) {
  const char* label = spec.name.c_str();
  std::optional<std::pair<std::string, med::ParameterValue>> edited;
  switch (spec.type) {
    case med::ParameterType::Flag: {
      bool on = table.flag(p, spec.name);
      if (ImGui::Checkbox(label, &on)) edited.emplace(spec.name, on);
      break;
    }
    case med::ParameterType::Integer: {
      int v = int(std::clamp<std::int64_t>(table.integer(p, spec.name), INT32_MIN, INT32_MAX));
      if (ImGui::InputInt(label, &v, 1, 16))
        edited.emplace(spec.name, std::int64_t(std::clamp(double(v), spec.min, spec.max)));
      break;
    }
    case med::ParameterType::Real: {
      double v = table.real(p, spec.name);
      if (ImGui::InputDouble(label, &v, 0.0, 0.0, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue)) {
        v = std::clamp(v, spec.min, spec.max);
        if (!(spec.minExclusive && v == spec.min)) edited.emplace(spec.name, v);
      }
      break;
    }
    case med::ParameterType::Choice: {
      const std::string current = table.choice(p, spec.name);
      if (ImGui::BeginCombo(label, current.c_str())) {
        for (const auto& c : spec.choices)
          if (ImGui::Selectable(c.empty() ? "(none)" : c.c_str(), c == current)) edited.emplace(spec.name, c);
        ImGui::EndCombo();
      }
      break;
    }
  }
  if (ImGui::IsItemHovered() && !spec.help.empty()) ImGui::SetTooltip("%s", spec.help.c_str());
  return edited;
}

}  // namespace

void Viewer::drawPanels() {
  drawViewerPanel();
  const std::uint32_t pw = paneWidth(width_);
  for (std::size_t i = 0; i < panes_.size(); ++i) drawPanePanel(i, pw);
}

namespace {

// The panels leave the picture to the user: they open collapsed, the
// viewer's at the window's top left and each viewport's at its pane's top
// right, so their title bars never overlap; opened, each fits its contents
// up to a quarter of the picture under it (0.45 x 0.55 of the pane) and
// scrolls beyond.
void placePanel(const ImVec2& at, const ImVec2& pivot, float paneWidth, float height) {
  ImGui::SetNextWindowPos(at, ImGuiCond_FirstUseEver, pivot);
  ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), ImVec2(0.45f * paneWidth, 0.55f * height));
}

}  // namespace

// The viewer's panel: the scene, the camera, lens and shutter, animation
// and the path tracer's convergence.
void Viewer::drawViewerPanel() {
  placePanel(ImVec2(8, 8), ImVec2(0, 0), float(paneWidth(width_)), float(height_));
  ImGui::Begin("tessera-viewer", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_HorizontalScrollbar);
  ImGui::PushItemWidth(160);
  ImGui::TextWrapped("%s", sceneName_.c_str());
  ImGui::Text("%.1f frames/s", ImGui::GetIO().Framerate);
  if (!status_.empty()) ImGui::TextWrapped("%s", status_.c_str());

  drawCameraSection();

  if (ImGui::CollapsingHeader("Lens and shutter")) {
    // Depth of field (path tracer): the aperture up to a tenth of the
    // scene's radius, the focus out to four radii; Ctrl+click focuses.
    auto* camera = session_->source.find<sg::Camera>(session_->camera);
    float aperture = camera->apertureRadius(), focus = camera->focusDistance();
    if (ImGui::SliderFloat("aperture", &aperture, 0.0f, std::max(0.1f * radius_, 1e-3f), "%.4g"))
      camera->setApertureRadius(std::max(aperture, 0.0f));
    if (ImGui::SliderFloat("focus", &focus, 1e-3f * radius_, 4.0f * radius_, "%.4g", ImGuiSliderFlags_Logarithmic))
      camera->setFocusDistance(std::max(focus, 1e-6f));
    ImGui::TextDisabled("Ctrl+click: focus there");
    // The shutter (path tracer): what the animation moves is blurred over
    // this part of the frame interval.
    float shutter[2] = {camera->shutterOpen(), camera->shutterClose()};
    if (ImGui::SliderFloat2("shutter", shutter, 0.0f, 1.0f, "%.2f"))
      setShutter(std::clamp(shutter[0], 0.0f, 1.0f), std::clamp(shutter[1], 0.0f, 1.0f));
  }

  if (animationDuration_ > 0 && ImGui::CollapsingHeader("Animation", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::Checkbox("Play", &playing_);
    float t = float(animationTime_);
    if (ImGui::SliderFloat("time (s)", &t, 0.0f, float(animationDuration_))) {
      playing_ = false;
      setAnimationTime(t);
    }
  }

  if (ImGui::CollapsingHeader("Path tracer", ImGuiTreeNodeFlags_DefaultOpen)) {
    int limit = int(convergence_.sampleLimit);
    if (ImGui::InputInt("sample limit", &limit, 16, 256))
      convergence_.sampleLimit = std::uint32_t(std::clamp(limit, 1, 1 << 20));
    if (ImGui::Button(convergence_.paused ? "Resume (Space)" : "Pause (Space)"))
      convergence_.paused = !convergence_.paused;
  }
  ImGui::PopItemWidth();
  ImGui::End();
}

// Framing, orbiting, the raster while moving, and the bookmarks.
void Viewer::drawCameraSection() {
  if (!ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (ImGui::Button("Frame scene (F)")) frameScene();
  ImGui::SameLine();
  if (ImGui::Button("Orbit 15")) orbit_.orbit(15.0f, 0.0f);
  bool rasterise = convergence_.rasterWhileMoving;
  if (ImGui::Checkbox("Rasterise while moving", &rasterise)) convergence_.rasterWhileMoving = rasterise;
  static char name[64] = "view";
  ImGui::SetNextItemWidth(140);
  ImGui::InputText("##bookmark", name, sizeof(name));
  ImGui::SameLine();
  if (ImGui::Button("Save bookmark")) {
    try {
      saveBookmark(name);
    } catch (const std::exception& e) {
      bookmarkMessage_ = std::string("error: ") + e.what();
    }
  }
  for (std::size_t i = 0; i < bookmarks_.bookmarks.size(); ++i) {
    const std::string label = std::to_string(i + 1) + ": " + bookmarks_.bookmarks[i].name;
    if (ImGui::Selectable(label.c_str())) loadBookmark(bookmarks_.bookmarks[i].name);
  }
  if (!bookmarkMessage_.empty()) ImGui::TextWrapped("%s", bookmarkMessage_.c_str());
}

// Viewport i's panel: its back-end, what it shows and costs, its
// parameters, and the objects it sees.
void Viewer::drawPanePanel(std::size_t i, std::uint32_t pw) {
  ViewerPane& pane = panes_[i];
  const std::string title = "Viewport " + std::to_string(i);
  placePanel(ImVec2(float(std::uint32_t(i) * pw + pw) - 8.0f, 8), ImVec2(1, 0), float(pw), float(height_));
  ImGui::Begin(title.c_str(), nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_HorizontalScrollbar);
  ImGui::PushItemWidth(160);
  const auto names = registry_.backends();
  if (ImGui::BeginCombo("back-end", pane.backend().c_str())) {
    for (const auto& name : names) {
      const std::string label = name + (pane.hasViewport(name) ? "  (converted)" : "");
      if (ImGui::Selectable(label.c_str(), name == pane.backend())) pane.setBackend(name);
    }
    ImGui::EndCombo();
  }
  const med::RenderStats& stats = pane.stats();
  ImGui::Text("showing %s%s, last render %.1f ms", pane.shownBackend().c_str(),
              pane.showingWhitted() ? " (Whitted until the path tracer catches up)" : "", stats.seconds * 1e3);
  if (pane.isRemote(pane.shownBackend())) {
    ImGui::Text("rendered on the cluster's nodes (%s)", options_.cluster.c_str());
    if (cluster_ && pane.frame().outputs.count(std::string(cluster::kWorkloadOutput))) {
      ImGui::Checkbox("workload over the image (O)", &showWorkload_);
      const cluster::FrameWorkload& w = cluster_->lastWorkload();
      ImGui::Text("balance %.2f (slowest node's render time over the mean)", w.balance);
      for (std::size_t n = 0; n < w.nodes.size(); ++n) {
        const glm::vec3 c = cluster::nodeColour(n);
        ImGui::TextColored(ImVec4(std::pow(c.r, 1 / 2.2f), std::pow(c.g, 1 / 2.2f), std::pow(c.b, 1 / 2.2f), 1),
                           "node %zu: %zu tiles, %.1f ms", n, w.nodes[n].tiles, w.nodes[n].seconds * 1e3);
      }
    }
  } else if (pane.progressive()) {
    ImGui::Text("%u spp of %u %s", pane.samples(), convergence_.sampleLimit,
                convergence_.paused ? "(paused)"
                : pane.converging() ? ""
                                    : "(done)");
    ImGui::Text("%.2f spp/s, %.2f Mrays/s (since restart)", pane.samplesPerSecond(), pane.raysPerSecond() * 1e-6);
  }
  if (!pane.isRemote(pane.backend()) && ImGui::CollapsingHeader("Parameters", ImGuiTreeNodeFlags_DefaultOpen)) {
    // Every parameter the back-end declares, in a scrolling list (the path
    // tracer has dozens); spp is the viewer's: the sample limit sets it.
    const med::ParameterTable& table = registry_.capabilities(pane.backend()).parameters;
    ImGui::BeginChild("parameters", ImVec2(360, std::min(200.0f, 26.0f * float(table.specs().size()))), true);
    for (const auto& spec : table.specs()) {
      if (spec.name == "spp") continue;
      try {
        if (auto edited = parameterControl(table, spec, pane.parameters()))
          pane.setParameter(registry_, edited->first, edited->second);
      } catch (const med::ParameterError& e) {
        status_ = e.what();
      }
    }
    ImGui::EndChild();
  }
  if (pane.frame().outputs.count(med::kIdOutput)) {
    const auto ranked = med::rankObjects(pane.frame(), session_->replica.scene());
    ImGui::Text("%zu objects seen; click one here or in the image", ranked.size());
    ImGui::BeginChild("ranking", ImVec2(260, 140), true);
    for (const auto& r : ranked) {
      char label[200];
      std::snprintf(label, sizeof(label), "%5.1f%%  %s##%llu", r.fraction * 100.0,
                    r.name.empty() ? ("#" + std::to_string(r.id)).c_str() : r.name.c_str(),
                    static_cast<unsigned long long>(r.id));
      if (ImGui::Selectable(label, r.id == selected_)) selected_ = r.id == selected_ ? sg::kNoContainer : r.id;
    }
    ImGui::EndChild();
  }
  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace tsr::app
