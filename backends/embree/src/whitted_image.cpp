#include "tsr/embree/whitted_image.hpp"

#include "tsr/embree/error.hpp"

namespace tsr::embree {

WhittedImage::WhittedImage(std::uint32_t width, std::uint32_t height) : width_(width), height_(height) {
  if (width == 0 || height == 0) throw Error("Whitted image size must be non-zero");
  const std::size_t n = std::size_t(width) * height;
  colour_.resize(n);
  depth_.resize(n);
  albedo_.resize(n);
  normal_.resize(n);
}

}  // namespace tsr::embree
