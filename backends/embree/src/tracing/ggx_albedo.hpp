#pragma once
// Directional albedo of single-scattering GGX reflection, tabulated once
// over (cos theta_o, alpha). With Schlick's Fresnel F0 + (F90 - F0)(1 - c)^5
// the albedo is exactly F0 * scale + F90 * bias, so one table serves metals
// (energy compensation after Kulla and Conty 2017) and the dielectric layer
// over the diffuse base (the diffuse keeps what the layer does not reflect).
// Private to the back-end.

namespace tsr::embree {

struct GgxAlbedo {
  float scale = 1.0f;                           // multiplies F0
  float bias = 0.0f;                            // multiplies F90
  float white() const { return scale + bias; }  // F = 1
};

// cosTheta in [0, 1], alpha in [0, 1]; bilinear in the table.
GgxAlbedo ggxAlbedo(float cosTheta, float alpha);
// The cosine-weighted hemispherical average of ggxAlbedo(.).white().
float ggxAverageAlbedo(float alpha);

}  // namespace tsr::embree
