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
  void setColorSpace(ColorSpace c) { set<&Image::colorSpace_>(c); }
  void setUri(std::string uri) { set<&Image::uri_>(std::move(uri)); }

  std::size_t expectedByteCount() const;
  std::optional<std::string> invalidReason() const;

  static constexpr auto fieldSpecs() {
    using M = Image;
    // The layout and the pixels change together, through setPixels; each
    // of these keeps the rest of the layout (pixels zeroed to fit), and
    // new pixels are read as one row of single bytes.
    constexpr auto kSetWidth = +[](M& i, std::uint32_t w) { i.relayout(w, i.height_, i.channels_, i.format_); };
    constexpr auto kSetHeight = +[](M& i, std::uint32_t h) { i.relayout(i.width_, h, i.channels_, i.format_); };
    constexpr auto kSetChannels = +[](M& i, std::uint32_t c) { i.relayout(i.width_, i.height_, c, i.format_); };
    constexpr auto kSetFormat = +[](M& i, PixelFormat f) { i.relayout(i.width_, i.height_, i.channels_, f); };
    constexpr auto kSetPixels = +[](M& i, std::vector<std::uint8_t> p) {
      auto n = static_cast<std::uint32_t>(p.size());
      i.setPixels(n, 1, 1, PixelFormat::UInt8, std::move(p));
    };
    return std::tuple{valueField(Width, "width", &M::width_, kSetWidth),
                      valueField(Height, "height", &M::height_, kSetHeight),
                      valueField(Channels, "channels", &M::channels_, kSetChannels),
                      valueField(Format, "format", &M::format_, kSetFormat),
                      valueField(Space, "colorSpace", &M::colorSpace_, &M::setColorSpace),
                      arrayField(Pixels, "pixels", &M::pixels_, kSetPixels),
                      valueField(Uri, "uri", &M::uri_, &M::setUri)};
  }

 private:
  void relayout(std::uint32_t width, std::uint32_t height, std::uint32_t channels, PixelFormat format) {
    std::size_t bytes = std::size_t{width} * height * channels * (format == PixelFormat::Float32 ? 4 : 1);
    setPixels(width, height, channels, format, std::vector<std::uint8_t>(bytes));
  }

  std::uint32_t width_ = 0;
  std::uint32_t height_ = 0;
  std::uint32_t channels_ = 4;
  PixelFormat format_ = PixelFormat::UInt8;
  ColorSpace colorSpace_ = ColorSpace::SRGB;
  std::vector<std::uint8_t> pixels_;
  std::string uri_;
};

}  // namespace tsr::sg
