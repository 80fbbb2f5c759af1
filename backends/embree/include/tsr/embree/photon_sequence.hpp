#pragma once

#include "tsr/embree/irradiance_field.hpp"
#include "tsr/embree/scene.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace tsr::embree {

// Spatio-temporal photon density estimation for animations (Weber et al.
// 2004, with the validity test of Myszkowski et al. 2001). Defaults in
// brackets are ours where the papers leave the choice to the user.
struct PhotonSettings {
  float elementSize = 0.0f;              // largest element edge (world units); 0 = scene diagonal / 40
  std::uint32_t maxElements = 1u << 18;  // caps the element count (levels shrink evenly)
  std::uint32_t tMax = 9;                // frames in the ring buffer; the window is centred, so odd
  std::uint32_t photonsPerFrame = 0;     // N_frame; 0 = from the pilot pass by eq. 3
  std::uint32_t pilotPhotons = 20000;    // N_pilot
  std::uint32_t budgetFrames = 0;        // frames sharing eq. 3's error budget; 0 = tMax
  float maxError = 0.1f;                 // E_max of eq. 3 (relative, energy-weighted over elements)
  float accuracy = 0.05f;                // sigma_% of eq. 4: the spatial support gathers 1/accuracy^2 photons
  std::uint32_t maxRings = 6;            // ring neighbourhoods at most, before the extra ring
  float influence = 0.3f;                // l of §5.1.3: sigma_I = l * I_t0(q), at least the noise
  float creaseAngle = 0.7f;              // radians: neighbourhoods and corners do not cross sharper edges
  float validityK = 2.0f;                // k of 002 eq. 1
  std::uint32_t minFrames = 3;           // 002: temporal extent at least 3 frames
  float emissionStep = 0.05f;            // a source's power changing more (relative) between frames ends every window
  std::uint32_t maxBounces = 8;
  std::uint64_t seed = 0;
  int threads = 0;  // 0 = all hardware threads

  void validate() const;  // throws Error
};

// Which photons a reconstruction uses: all, or the even or odd half-set
// (for the perceptual stopping rule, 002 §5.2.3).
enum class PhotonHalf { All, Even, Odd };

struct FrameStats {
  std::uint64_t photons = 0;  // traced for this frame
  std::uint64_t hits = 0;     // recorded on elements
  std::uint64_t rays = 0;
};

struct Reconstruction {
  IrradianceField field;
  // Per element: frames collected before and after the reconstructed one
  // (the validity test's extents), and the rings of its spatial support.
  std::vector<std::uint8_t> backward, forward, rings;
  float spatialFallback = 0.0f;  // fraction of lit elements whose temporal extent was cut
};

// Photon passes over an animation, frame by frame, and the reconstruction
// of each frame's indirect irradiance from the frames around it.
//
//   PhotonSequence seq(settings);
//   for f in [0, frames + seq.lookahead()):
//     if f < frames: pose(scene, f); seq.addFrame(scene, f);
//     g = f - seq.lookahead();
//     if g >= 0: field = seq.reconstruct(g).field; pose(scene, g);
//                renderer.renderWithIrradiance(scene, camera, region, fb, field);
//
// The scene is edited between frames through its normal setters (instance
// transforms, materials, lights, vertex updates); its instances and mesh
// topology must stay those of the first frame (elements are fixed).
class PhotonSequence {
 public:
  explicit PhotonSequence(PhotonSettings settings = {});
  ~PhotonSequence();
  PhotonSequence(PhotonSequence&&) noexcept;
  PhotonSequence& operator=(PhotonSequence&&) noexcept;

  // Commits the scene and traces this frame's photons. The first call builds
  // the elements and, without a fixed photonsPerFrame, runs the pilot pass.
  // Frames must be consecutive. Photons carry a fixed energy set at the
  // first frame, so a brighter light sends more photons (counts stay
  // proportional to energy, as the validity test needs).
  FrameStats addFrame(Scene& scene, std::int64_t frame);

  // Frames after g that reconstruct(g) reads: (tMax - 1) / 2.
  std::uint32_t lookahead() const;
  // Reconstructs a buffered frame (within the last tMax added) from the
  // buffered frames around it. Deterministic for any thread count.
  Reconstruction reconstruct(std::int64_t frame, PhotonHalf half = PhotonHalf::All) const;

  // One buffered frame's unfiltered element irradiance (energy / area):
  // what density estimation without any filtering would give.
  std::vector<glm::vec3> rawIrradiance(std::int64_t frame) const;
  // A field of given element irradiance (one value per element, as
  // rawIrradiance gives), interpolated across elements as reconstruct()'s
  // are: how irradiance denoised elsewhere (object-space PCA) is looked up
  // at render time. Corners weigh the elements around them by area and
  // normal at the newest frame's pose, the same at every pose for rigid
  // motion; for deforming meshes the newest pose stands for all.
  IrradianceField field(std::vector<glm::vec3> irradiance) const;

  // The luminance of the power all sources emit in a buffered frame (known
  // exactly, not estimated).
  float emittedPower(std::int64_t frame) const;
  std::uint32_t photonsPerFrame() const;  // N_frame, after the first addFrame
  float pilotError() const;               // E_pilot, 0 without a pilot pass
  std::size_t elementCount() const;
  const PhotonSettings& settings() const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace tsr::embree
