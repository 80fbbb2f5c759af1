#pragma once
// The path tracer with indirect light from spatio-temporal photon density
// estimation (viewport parameter temporal = "photons"; Weber et al. 2004
// with Myszkowski et al.'s validity test): photons are traced in a second
// copy of the scene that prepare() poses lookahead() frames ahead, and each
// frame shown samples direct light per pixel and reads indirect light from
// the irradiance reconstructed over the frames around it, so it does not
// flicker as frame-by-frame path tracing does.
//
// Parameters besides the path tracer's: spp (direct-light samples per
// pixel, default 16), photonsPerFrame (0: chosen by a pilot pass, Weber
// eq. 3), photonFrames (the odd temporal window t_max, default 9),
// photonAccuracy (sigma_% of eq. 4, default 0.05), photonMaxError (E_max
// of eq. 3, default 0.1), photonEmissionStep (a light's power changing by
// more than this fraction between frames ends every temporal window there,
// default 0.05).
#include "embree_scene_adapter.hpp"
#include "tsr/embree/photon_sequence.hpp"
#include "tsr/embree/renderer.hpp"
#include "tsr/med/viewport.hpp"

namespace tsr::med::embree_mediator {

embree::PhotonSettings photonSettingsFrom(const Parameters& parameters);

class PhotonViewport final : public Viewport {
 public:
  PhotonViewport(ViewportSettings settings, const std::shared_ptr<embree::Device>& device);

  std::uint32_t lookahead() const override { return photons_.lookahead(); }
  void prepare(const sg::Replica& ahead, std::int64_t frame) override;
  SceneAdapter::Update synchronize(const sg::Replica& replica) override;
  // Needs control.frame: a prepared frame within the last photonFrames.
  RenderStats render(const sg::Replica& replica, const View& view, FrameBuffer& out,
                     const RenderControl& control) override;
  std::vector<std::string> outputNames() const override;

 private:
  EmbreeSceneAdapter ahead_;  // posed at the newest prepared frame
  EmbreeSceneAdapter shown_;  // posed at the frame rendered
  embree::PhotonSequence photons_;
  embree::Renderer renderer_;
};

}  // namespace tsr::med::embree_mediator
