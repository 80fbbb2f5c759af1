#pragma once
// Texture or environment pixels, shared by every material that names them.
#include <optional>
#include <string>
#include <vector>

#include "tsr/sg/container_of.hpp"

namespace tsr::sg {

enum class PixelFormat : std::uint8_t { UInt8, Float32, Count };
enum class ColorSpace : std::uint8_t { SRGB, Linear, Count };

class Image final : public ContainerOf<Image, ContainerType::Image> {
 public:
  enum Field : FieldIndex { Width = kFirstOwnField, Height, Channels, Format, Space, Pixels, Uri };

  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  std::uint32_t channels() const { return channels_; }
  PixelFormat format() const { return format_; }
  ColorSpace colorSpace() const { return colorSpace_; }
  // Row-major, top row first, channels interleaved; floats as 4 bytes each.
  const std::vector<std::uint8_t>& pixels() const { return pixels_; }
  const std::string& uri() const { return uri_; }

  // Sets the size, layout and pixels at once; throws SceneError when the
  // byte count does not match.
  void setPixels(std::uint32_t width, std::uint32_t height, std::uint32_t channels, PixelFormat format,
                 std::vector<std::uint8_t> pixels);
  void setColorSpace(ColorSpace c) { assign(Space, colorSpace_, c); }
  void setUri(std::string uri) { assign(Uri, uri_, std::move(uri)); }

  std::size_t expectedByteCount() const;
  std::optional<std::string> invalidReason() const;

  static constexpr auto fieldSpecs() {
    return std::tuple{valueField("width", &Image::width_),
                      valueField("height", &Image::height_),
                      valueField("channels", &Image::channels_),
                      valueField("format", &Image::format_),
                      valueField("colorSpace", &Image::colorSpace_),
                      arrayField("pixels", &Image::pixels_),
                      valueField("uri", &Image::uri_)};
  }

 private:
  std::uint32_t width_ = 0;
  std::uint32_t height_ = 0;
  std::uint32_t channels_ = 4;
  PixelFormat format_ = PixelFormat::UInt8;
  ColorSpace colorSpace_ = ColorSpace::SRGB;
  std::vector<std::uint8_t> pixels_;
  std::string uri_;
};

}  // namespace tsr::sg
