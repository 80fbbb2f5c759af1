#pragma once
// tessera-render's temporal noise reduction options (with --frames):
//   --temporal pca|photons   denoise the indirect light over the sequence
//   --temporal reproject     each frame adds --spp samples to the last one's, reprojected
//   --direct-spp N           samples of direct light per frame
//   --temporal-modes M       fixed PCA truncation (default: automatic, 2.3)
//   --temporal-epsilon E, --temporal-epsilon-change C, --temporal-global,
//   --temporal-map-sigma S, --temporal-window W, --temporal-overlap O
//   --photons-per-frame N, --photon-frames T (photons)
//   --temporal-space auto|image|object (pca)
//   --temporal-high-spp N, --temporal-m-min M (pca, image space: 3.2's importance sampling)
#include <CLI/CLI.hpp>

#include <algorithm>
#include <string>

#include "tsr/med/parameters.hpp"

namespace tsr::app {

struct TemporalOptions {
  std::string method;  // empty: frame by frame
  int directSpp = 0;   // 0: the same as --spp (see --help)
  int modes = 0;       // 0: automatic
  double epsilon = 0.005, epsilonChange = 0.001;
  bool plainRule = false;  // --temporal-plain-rule: no noise measurement
  bool global = false;     // one truncation for the whole frame instead of 3.2's map
  double mapSigma = 2.0;
  int window = 64;
  int overlap = -1;  // -1: a quarter of the window, at most 16 (overlapFrames())
  int overlapFrames() const { return overlap >= 0 ? overlap : std::min(16, window / 4); }
  int highSpp = 0;          // 3.2's importance sampling: samples of the re-render (0: off)
  double mMin = 0;          // pixels whose map keeps more modes get it; 0: half the window's frames
  int photonsPerFrame = 0;  // 0: from the photon pilot pass
  int photonFrames = 9;     // the photon method's temporal window (odd)
  // Where pca projects: image (the rendered frames' indirect output, on the
  // client), object (irradiance on surface elements, in the path tracer) or
  // auto: object when the camera moves during the sequence.
  std::string space = "auto";
  bool active() const { return !method.empty(); }
  // pca on the rendered frames, in the application.
  bool imagePca() const { return method == "pca" && space == "image"; }
  // The method runs in the path tracer's temporal viewport.
  bool inBackend() const { return method == "photons" || (method == "pca" && space == "object"); }
  // The path tracer's history carries each frame's samples to the next.
  bool reprojects() const { return method == "reproject"; }
  // Settles space "auto" (pca only): object when the camera moves.
  void resolveSpace(bool cameraMoves);
  // The viewport parameters that select the method in the back-end
  // (photons, or object-space pca: the path tracer's temporal viewport;
  // reproject: its history); none for image-space pca, which works on the
  // rendered frames.
  void applyTo(med::Parameters& parameters) const;
};

// Declares the options on `app` (so --help lists them), in their own group.
void addTemporalOptions(CLI::App& app, TemporalOptions& options);

// Checks combinations CLI11 cannot: throws std::invalid_argument. Those that
// depend on the space are checked again once it is resolved.
void checkTemporalOptions(const TemporalOptions& options, int spp);

}  // namespace tsr::app
