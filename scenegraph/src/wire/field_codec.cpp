#include "tsr/sg/wire/field_codec.hpp"

namespace tsr::sg::codec {

namespace {
enum class AttachmentTag : std::uint8_t { Integer = 0, Real = 1, Text = 2, Floats = 3 };
}

void write(ByteWriter& w, const Attachments& attachments) {
  w.varint(attachments.size());
  for (const auto& [key, value] : attachments) {
    w.string(key);
    std::visit(
        [&](const auto& v) {
          using V = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<V, std::int64_t>) {
            w.u8(static_cast<std::uint8_t>(AttachmentTag::Integer));
            w.svarint(v);
          } else if constexpr (std::is_same_v<V, double>) {
            w.u8(static_cast<std::uint8_t>(AttachmentTag::Real));
            w.f64(v);
          } else if constexpr (std::is_same_v<V, std::string>) {
            w.u8(static_cast<std::uint8_t>(AttachmentTag::Text));
            w.string(v);
          } else {
            w.u8(static_cast<std::uint8_t>(AttachmentTag::Floats));
            w.varint(v.size());
            w.raw(v.data(), v.size() * sizeof(float));
          }
        },
        value);
  }
}

void read(ByteReader& r, Attachments& attachments, FieldReadContext& ctx) {
  std::size_t n = r.count(ctx.limits.maxAttachments, 2, "attachment");
  Attachments result;
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t at = r.offset();
    std::string key = r.string(ctx.limits.maxStringBytes);
    if (key.empty()) throw DecodeError(at, "attachment with an empty name");
    std::uint8_t tag = r.u8();
    AttachmentValue value;
    switch (static_cast<AttachmentTag>(tag)) {
      case AttachmentTag::Integer:
        value = r.svarint();
        break;
      case AttachmentTag::Real:
        value = r.f64();
        break;
      case AttachmentTag::Text:
        value = r.string(ctx.limits.maxStringBytes);
        break;
      case AttachmentTag::Floats: {
        std::size_t count = r.count(ctx.limits.maxArrayElements, sizeof(float), "attachment float");
        std::vector<float> floats(count);
        for (auto& f : floats) f = r.f32();
        value = std::move(floats);
        break;
      }
      default:
        r.fail("unknown attachment value tag " + std::to_string(tag));
    }
    if (!result.emplace(std::move(key), std::move(value)).second) throw DecodeError(at, "attachment name repeated");
  }
  attachments = std::move(result);
}

}  // namespace tsr::sg::codec
