#include "tsr/cluster/field_codecs.hpp"

#include <stdexcept>
#include <variant>

namespace tsr::cluster::codec {

namespace {
std::uint32_t readCoordinate(sg::ByteReader& r, std::uint32_t max, const char* what) {
  std::uint32_t v = 0;
  Varint{max}.read(r, v, what, 0);
  return v;
}
}  // namespace

void writeRect(sg::ByteWriter& w, const med::PixelRect& rect) {
  w.varint(rect.x0);
  w.varint(rect.y0);
  w.varint(rect.x1);
  w.varint(rect.y1);
}

med::PixelRect readRect(sg::ByteReader& r, std::uint32_t width, std::uint32_t height, RectLimits limits) {
  std::size_t at = r.offset();
  med::PixelRect rect;
  rect.x0 = readCoordinate(r, limits.maxSide, "rect x0");
  rect.y0 = readCoordinate(r, limits.maxSide, "rect y0");
  rect.x1 = readCoordinate(r, limits.maxSide, "rect x1");
  rect.y1 = readCoordinate(r, limits.maxSide, "rect y1");
  if (rect.empty()) throw sg::DecodeError(at, "empty pixel rectangle");
  if (rect.x1 > width || rect.y1 > height) throw sg::DecodeError(at, "pixel rectangle outside the image");
  if (std::uint64_t{rect.width()} * rect.height() > limits.maxPixels)
    throw sg::DecodeError(at, "pixel rectangle larger than " + std::to_string(limits.maxPixels) + " pixels");
  return rect;
}

void writeView(sg::ByteWriter& w, const med::View& v) {
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) w.f32(v.cameraToWorld[c][row]);
  for (float f : {v.left, v.right, v.bottom, v.top, v.nearPlane, v.farPlane, v.apertureRadius, v.focusDistance,
                  v.shutterOpen, v.shutterClose})
    w.f32(f);
  w.u8(v.cameraToWorldAtEnd ? 1 : 0);
  if (v.cameraToWorldAtEnd)
    for (int c = 0; c < 4; ++c)
      for (int row = 0; row < 4; ++row) w.f32((*v.cameraToWorldAtEnd)[c][row]);
  w.varint(v.width);
  w.varint(v.height);
  writeRect(w, v.region);
}

med::View readView(sg::ByteReader& r, RectLimits limits) {
  std::size_t at = r.offset();
  med::View v;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) v.cameraToWorld[c][row] = r.f32();
  for (float* f : {&v.left, &v.right, &v.bottom, &v.top, &v.nearPlane, &v.farPlane, &v.apertureRadius, &v.focusDistance,
                   &v.shutterOpen, &v.shutterClose})
    *f = r.f32();
  switch (r.u8()) {
    case 0:
      break;
    case 1: {
      glm::mat4 end;
      for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) end[c][row] = r.f32();
      v.cameraToWorldAtEnd = end;
      break;
    }
    default:
      r.fail("camera motion flag not 0 or 1");
  }
  v.width = readCoordinate(r, limits.maxSide, "image width");
  v.height = readCoordinate(r, limits.maxSide, "image height");
  v.region = readRect(r, v.width, v.height, limits);
  try {
    v.validate();
  } catch (const std::invalid_argument& e) {
    throw sg::DecodeError(at, e.what());
  }
  return v;
}

void writeParameters(sg::ByteWriter& w, const med::Parameters& p) {
  w.varint(p.all().size());
  for (const auto& [name, value] : p.all()) {
    w.string(name);
    w.u8(static_cast<std::uint8_t>(value.index()));
    std::visit(
        [&](const auto& x) {
          using T = std::decay_t<decltype(x)>;
          if constexpr (std::is_same_v<T, bool>)
            w.u8(x ? 1 : 0);
          else if constexpr (std::is_same_v<T, std::int64_t>)
            w.svarint(x);
          else if constexpr (std::is_same_v<T, double>)
            w.f64(x);
          else
            w.string(x);
        },
        value);
  }
}

med::Parameters readParameters(sg::ByteReader& r, std::size_t maxCount, std::size_t maxNameBytes,
                               std::size_t maxStringBytes) {
  med::Parameters p;
  std::size_t n = r.count(maxCount, 3, "parameter");
  for (std::size_t i = 0; i < n; ++i) {
    std::string name = r.string(maxNameBytes);
    if (name.empty()) r.fail("empty parameter name");
    std::size_t at = r.offset();
    switch (r.u8()) {
      case 0: {
        std::uint8_t b = r.u8();
        if (b > 1) r.fail("boolean parameter not 0 or 1");
        p.set(name, b == 1);
        break;
      }
      case 1:
        p.set(name, r.svarint());
        break;
      case 2:
        p.set(name, r.f64());
        break;
      case 3:
        p.set(name, r.string(maxStringBytes));
        break;
      default:
        throw sg::DecodeError(at, "unknown parameter kind");
    }
  }
  return p;
}

}  // namespace tsr::cluster::codec
