#pragma once
// The path tracer with indirect light denoised over time on surface
// elements fixed in object space: photons are traced in a second copy of
// the scene that prepare() poses lookahead() frames ahead, and each frame
// shown samples direct light per pixel and reads indirect light from the
// elements' irradiance, so it does not flicker as frame-by-frame path
// tracing does. The viewport parameter temporal names how that irradiance
// is denoised:
//  - "photons": spatio-temporal photon density estimation (Weber et al.
//    2004 with Myszkowski et al.'s validity test) over the frames around it;
//  - "objectPca": Meyer & Anderson's basis projection (3.1, moving cameras)
//    of each element's noisy per-frame irradiance (its photons' energy over
//    its area) over windows of pcaWindow frames. The elements are the point
//    set: fixed on the meshes, so visibility changes of a moving camera are
//    not mistaken for lighting changes; they move with their instances and
//    deform with their meshes (the rest topology is the reference object).
//    One truncation per window (2.3's rule; pcaModes fixes it): 3.2's map
//    smooths over image neighbours, which elements in a list do not have.
//    Projected per unit of the frame's emitted power, which is known
//    exactly, so a light switch stays a step.
//
// Parameters besides the path tracer's: spp (direct-light samples per
// pixel, default 16), photonsPerFrame (0: chosen by a pilot pass, Weber
// eq. 3), photonFrames (the odd temporal window t_max, default 9),
// photonAccuracy (sigma_% of eq. 4, default 0.05), photonMaxError (E_max
// of eq. 3, default 0.1), photonEmissionStep (a light's power changing by
// more than this fraction between frames ends every temporal window there,
// default 0.05). With objectPca: pcaWindow (default 64), pcaOverlap
// (default: a quarter of the window, at most 16), pcaModes (0:
// automatic), pcaEpsilon, pcaEpsilonChange, pcaPlainRule (tsr::temporal's
// rule, see backends/temporal/README.md), and photonsPerFrame's pilot
// shares eq. 3's budget over the window.
#include <map>
#include <optional>

#include "embree_scene_adapter.hpp"
#include "tsr/embree/photon_sequence.hpp"
#include "tsr/embree/renderer.hpp"
#include "tsr/med/viewport.hpp"
#include "tsr/temporal/windowed_pca.hpp"

namespace tsr::med::embree_mediator {

embree::PhotonSettings photonSettingsFrom(const Parameters& parameters);

class PhotonViewport final : public Viewport {
 public:
  PhotonViewport(ViewportSettings settings, const std::shared_ptr<embree::Device>& device);

  std::uint32_t lookahead() const override;
  void prepare(const sg::Replica& ahead, std::int64_t frame) override;
  SceneAdapter::Update synchronize(const sg::Replica& replica) override;
  // Needs control.frame: a prepared frame within the last photonFrames.
  RenderStats render(const sg::Replica& replica, const View& view, FrameBuffer& out,
                     const RenderControl& control) override;
  std::vector<std::string> outputNames() const override;

 private:
  const embree::IrradianceField& field(std::int64_t frame);
  void keep(std::vector<temporal::DenoisedFrame> denoised);

  EmbreeSceneAdapter ahead_;  // posed at the newest prepared frame
  EmbreeSceneAdapter shown_;  // posed at the frame rendered
  embree::PhotonSequence photons_;
  embree::Renderer renderer_;
  // objectPca: the element irradiance denoised so far, by frame, until shown.
  std::optional<temporal::WindowedPca> pca_;
  std::int64_t firstFrame_ = -1;
  std::map<std::int64_t, std::vector<glm::vec3>> denoised_;
  std::map<std::int64_t, float> power_;  // emitted by the frames in the projection
  std::optional<std::pair<std::int64_t, embree::IrradianceField>> shownField_;  // the frame last shown
};

}  // namespace tsr::med::embree_mediator
