#include "tsr/cluster/messages.hpp"

#include <algorithm>
#include <exception>
#include <stdexcept>

#include "tsr/cluster/protocol_error.hpp"
#include "tsr/sg/errors.hpp"

namespace tsr::cluster {

namespace {

template <std::size_t N>
void writeBytes(sg::ByteWriter& w, const std::array<std::uint8_t, N>& a) {
  w.raw(a.data(), N);
}
template <std::size_t N>
void readBytes(sg::ByteReader& r, std::array<std::uint8_t, N>& a, const char* what) {
  r.copy(a.data(), N, what);
}

std::uint32_t readU32Varint(sg::ByteReader& r, std::uint32_t max, const char* what) {
  std::size_t at = r.offset();
  std::uint64_t v = r.varint();
  if (v > max)
    throw sg::DecodeError(at, std::string(what) + " " + std::to_string(v) + " exceeds " + std::to_string(max));
  return static_cast<std::uint32_t>(v);
}

// An animation frame number: far beyond any sequence a person renders, yet
// well inside std::int64_t.
constexpr std::uint64_t kMaxSequenceFrame = std::uint64_t{1} << 40;
std::int64_t readSequenceFrame(sg::ByteReader& r) {
  std::size_t at = r.offset();
  std::uint64_t v = r.varint();
  if (v > kMaxSequenceFrame)
    throw sg::DecodeError(at, "animation frame " + std::to_string(v) + " exceeds " + std::to_string(kMaxSequenceFrame));
  return static_cast<std::int64_t>(v);
}

void writeRect(sg::ByteWriter& w, const med::PixelRect& rect) {
  w.varint(rect.x0);
  w.varint(rect.y0);
  w.varint(rect.x1);
  w.varint(rect.y1);
}

med::PixelRect readRect(sg::ByteReader& r, std::uint32_t width, std::uint32_t height) {
  std::size_t at = r.offset();
  med::PixelRect rect;
  rect.x0 = readU32Varint(r, kMaxImageSide, "rect x0");
  rect.y0 = readU32Varint(r, kMaxImageSide, "rect y0");
  rect.x1 = readU32Varint(r, kMaxImageSide, "rect x1");
  rect.y1 = readU32Varint(r, kMaxImageSide, "rect y1");
  if (rect.empty()) throw sg::DecodeError(at, "empty pixel rectangle");
  if (rect.x1 > width || rect.y1 > height) throw sg::DecodeError(at, "pixel rectangle outside the image");
  if (std::uint64_t{rect.width()} * rect.height() > kMaxRectPixels)
    throw sg::DecodeError(at, "pixel rectangle larger than " + std::to_string(kMaxRectPixels) + " pixels");
  return rect;
}

void writeView(sg::ByteWriter& w, const med::View& v) {
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) w.f32(v.cameraToWorld[c][row]);
  for (float f : {v.left, v.right, v.bottom, v.top, v.nearPlane, v.farPlane}) w.f32(f);
  w.varint(v.width);
  w.varint(v.height);
  writeRect(w, v.region);
}

med::View readView(sg::ByteReader& r) {
  std::size_t at = r.offset();
  med::View v;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) v.cameraToWorld[c][row] = r.f32();
  for (float* f : {&v.left, &v.right, &v.bottom, &v.top, &v.nearPlane, &v.farPlane}) *f = r.f32();
  v.width = readU32Varint(r, kMaxImageSide, "image width");
  v.height = readU32Varint(r, kMaxImageSide, "image height");
  v.region = readRect(r, v.width, v.height);
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

med::Parameters readParameters(sg::ByteReader& r) {
  med::Parameters p;
  std::size_t n = r.count(kMaxParameters, 3, "parameter");
  for (std::size_t i = 0; i < n; ++i) {
    std::string name = r.string(kMaxNameBytes);
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
        p.set(name, r.string(kMaxReasonBytes));
        break;
      default:
        throw sg::DecodeError(at, "unknown parameter kind");
    }
  }
  return p;
}

Compression readCompression(sg::ByteReader& r) {
  std::size_t at = r.offset();
  std::uint8_t c = r.u8();
  if (c > static_cast<std::uint8_t>(Compression::Kept))
    throw sg::DecodeError(at, "unknown compression " + std::to_string(c));
  return static_cast<Compression>(c);
}

bool readBool(sg::ByteReader& r, const char* what) {
  std::uint8_t b = r.u8();
  if (b > 1) r.fail(std::string(what) + " not 0 or 1");
  return b == 1;
}

void writeOutputNames(sg::ByteWriter& w, const std::vector<std::string>& names) {
  w.varint(names.size());
  for (const auto& n : names) w.string(n);
}

// Distinct, non-empty names: each is one image in the tile's pixels.
std::vector<std::string> readOutputNames(sg::ByteReader& r) {
  std::vector<std::string> names(r.count(kMaxOutputs, 2, "output name"));
  for (auto& n : names) {
    n = r.string(kMaxNameBytes);
    if (n.empty()) r.fail("empty output name");
    if (std::count(names.data(), &n, n) != 0) r.fail("output '" + n + "' named twice");
  }
  return names;
}

double readSeconds(sg::ByteReader& r) {
  std::size_t at = r.offset();
  double s = r.f64();
  if (s < 0) throw sg::DecodeError(at, "negative time");
  return s;
}

}  // namespace

void Hello::write(sg::ByteWriter& w) const {
  w.u8(version);
  writeBytes(w, clientNonce);
  w.string(clientName);
}
Hello Hello::read(sg::ByteReader& r) {
  Hello h;
  h.version = r.u8();
  readBytes(r, h.clientNonce, "client nonce");
  h.clientName = r.string(kMaxNameBytes);
  return h;
}

void Challenge::write(sg::ByteWriter& w) const {
  writeBytes(w, nodeNonce);
  writeBytes(w, nodeProof);
}
Challenge Challenge::read(sg::ByteReader& r) {
  Challenge c;
  readBytes(r, c.nodeNonce, "node nonce");
  readBytes(r, c.nodeProof, "node proof");
  return c;
}

void Auth::write(sg::ByteWriter& w) const { writeBytes(w, clientProof); }
Auth Auth::read(sg::ByteReader& r) {
  Auth a;
  readBytes(r, a.clientProof, "client proof");
  return a;
}

void Welcome::write(sg::ByteWriter& w) const {
  w.string(nodeName);
  w.varint(threads);
  w.varint(backends.size());
  for (const auto& b : backends) w.string(b);
}
Welcome Welcome::read(sg::ByteReader& r) {
  Welcome m;
  m.nodeName = r.string(kMaxNameBytes);
  m.threads = readU32Varint(r, 1 << 16, "thread count");
  std::size_t n = r.count(kMaxBackends, 1, "back-end");
  for (std::size_t i = 0; i < n; ++i) m.backends.push_back(r.string(kMaxNameBytes));
  return m;
}

void Reject::write(sg::ByteWriter& w) const { w.string(reason); }
Reject Reject::read(sg::ByteReader& r) { return {r.string(kMaxReasonBytes)}; }

void Applied::write(sg::ByteWriter& w) const { w.varint(version); }
Applied Applied::read(sg::ByteReader& r) { return {r.varint()}; }

void SetViewports::write(sg::ByteWriter& w) const {
  w.varint(viewports.size());
  for (const auto& v : viewports) {
    w.varint(v.id);
    w.string(v.backend);
    w.varint(v.root);
    w.varint(v.background);
    writeParameters(w, v.parameters);
  }
  w.u8(window ? 1 : 0);
  if (window) {
    w.svarint(window->x);
    w.svarint(window->y);
    w.varint(window->width);
    w.varint(window->height);
    w.u8(window->fullscreen ? 1 : 0);
  }
}
SetViewports SetViewports::read(sg::ByteReader& r) {
  SetViewports m;
  std::size_t n = r.count(kMaxViewports, 5, "viewport");
  for (std::size_t i = 0; i < n; ++i) {
    ViewportSpec v;
    v.id = readU32Varint(r, kMaxViewports * 1024, "viewport id");
    for (const auto& seen : m.viewports)
      if (seen.id == v.id) r.fail("viewport id " + std::to_string(v.id) + " given twice");
    v.backend = r.string(kMaxNameBytes);
    if (v.backend.empty()) r.fail("empty back-end name");
    v.root = r.varint();
    v.background = r.varint();
    v.parameters = readParameters(r);
    m.viewports.push_back(std::move(v));
  }
  std::uint8_t hasWindow = r.u8();
  if (hasWindow > 1) r.fail("window flag must be 0 or 1");
  if (hasWindow) {
    WindowPlacement wp;
    const std::int64_t limit = kMaxImageSide;
    for (std::int32_t* v : {&wp.x, &wp.y}) {
      std::int64_t p = r.svarint();
      if (p < -limit || p > limit) r.fail("window position beyond +-" + std::to_string(kMaxImageSide));
      *v = static_cast<std::int32_t>(p);
    }
    wp.width = readU32Varint(r, kMaxImageSide, "window width");
    wp.height = readU32Varint(r, kMaxImageSide, "window height");
    std::uint8_t full = r.u8();
    if (full > 1) r.fail("fullscreen flag must be 0 or 1");
    wp.fullscreen = full == 1;
    m.window = wp;
  }
  return m;
}

void RenderRequest::write(sg::ByteWriter& w) const {
  w.varint(frame);
  w.u8(static_cast<std::uint8_t>(compression));
  w.varint(jobs.size());
  for (const auto& j : jobs) {
    w.varint(j.viewport);
    writeView(w, j.view);
    w.varint(j.rects.size());
    for (const auto& rect : j.rects) writeRect(w, rect);
    writeOutputNames(w, j.outputs);
    w.u8(j.resolve ? 1 : 0);
  }
  w.varint(static_cast<std::uint64_t>(sequenceFrame + 1));  // 0: none
}
RenderRequest RenderRequest::read(sg::ByteReader& r) {
  RenderRequest m;
  m.frame = r.varint();
  m.compression = readCompression(r);
  std::size_t n = r.count(kMaxJobs, 100, "render job");
  for (std::size_t i = 0; i < n; ++i) {
    RenderJob j;
    j.viewport = readU32Varint(r, kMaxViewports * 1024, "viewport id");
    j.view = readView(r);
    std::size_t rects = r.count(kMaxRectsPerJob, 4, "rectangle");
    for (std::size_t k = 0; k < rects; ++k) j.rects.push_back(readRect(r, j.view.width, j.view.height));
    j.outputs = readOutputNames(r);
    j.resolve = readBool(r, "resolve flag");
    m.jobs.push_back(std::move(j));
  }
  m.sequenceFrame = readSequenceFrame(r) - 1;
  return m;
}

void Prepare::write(sg::ByteWriter& w) const {
  w.varint(static_cast<std::uint64_t>(frame));
  w.raw(changes.data(), changes.size());
}
Prepare Prepare::read(sg::ByteReader& r) {
  Prepare m;
  m.frame = readSequenceFrame(r);
  auto rest = r.take(r.remaining(), "change list");
  m.changes.assign(rest.begin(), rest.end());  // decoded by sg::decode, bounded as Changes are
  return m;
}

void RenderTile::write(sg::ByteWriter& w) const {
  w.varint(frame);
  w.varint(viewport);
  writeRect(w, rect);
  w.f64(seconds);
  writeOutputNames(w, outputs);
  w.u8(static_cast<std::uint8_t>(compression));
  w.raw(pixels.data(), pixels.size());
}
RenderTile RenderTile::read(sg::ByteReader& r) {
  RenderTile m;
  m.frame = r.varint();
  m.viewport = readU32Varint(r, kMaxViewports * 1024, "viewport id");
  m.rect = readRect(r, kMaxImageSide, kMaxImageSide);
  m.seconds = readSeconds(r);
  m.outputs = readOutputNames(r);
  m.compression = readCompression(r);
  if (m.compression == Compression::Kept && r.remaining() != 0)
    throw sg::DecodeError(r.offset(), "pixels kept on the node, yet the tile carries bytes");
  auto rest = r.take(r.remaining(), "pixels");
  m.pixels.assign(rest.begin(), rest.end());  // sizes are checked by decodePixels
  return m;
}

void FrameDone::write(sg::ByteWriter& w) const {
  w.varint(frame);
  w.f64(busySeconds);
}
FrameDone FrameDone::read(sg::ByteReader& r) {
  FrameDone m;
  m.frame = r.varint();
  m.busySeconds = readSeconds(r);
  return m;
}

void Swap::write(sg::ByteWriter& w) const { w.varint(frame); }
Swap Swap::read(sg::ByteReader& r) { return {r.varint()}; }

void HashQuery::write(sg::ByteWriter& w) const { w.varint(token); }
HashQuery HashQuery::read(sg::ByteReader& r) { return {r.varint()}; }

void HashReply::write(sg::ByteWriter& w) const {
  w.varint(token);
  w.varint(version);
  w.raw(&hash, sizeof hash);
}
HashReply HashReply::read(sg::ByteReader& r) {
  HashReply m;
  m.token = r.varint();
  m.version = r.varint();
  r.copy(&m.hash, sizeof m.hash, "content hash");
  return m;
}

void Heartbeat::write(sg::ByteWriter& w) const { w.varint(sequence); }
Heartbeat Heartbeat::read(sg::ByteReader& r) { return {r.varint()}; }
void HeartbeatAck::write(sg::ByteWriter& w) const { w.varint(sequence); }
HeartbeatAck HeartbeatAck::read(sg::ByteReader& r) { return {r.varint()}; }

void ErrorReport::write(sg::ByteWriter& w) const { w.string(reason); }
ErrorReport ErrorReport::read(sg::ByteReader& r) { return {r.string(kMaxReasonBytes)}; }

Frame frameFromPayload(MessageType type, std::span<const std::uint8_t> payload) {
  if (payload.size() > spec(type).maxPayload)
    throw ProtocolError(
        ProtocolError::Kind::Oversized,
        std::string(name(type)) + " of " + std::to_string(payload.size()) + " bytes exceeds its maximum");
  auto bytes = std::make_shared<std::vector<std::uint8_t>>();
  bytes->reserve(kFrameHeaderBytes + payload.size());
  writeFrameHeader(*bytes, {kProtocolVersion, type, static_cast<std::uint32_t>(payload.size())});
  bytes->insert(bytes->end(), payload.begin(), payload.end());
  return bytes;
}

void checkDecodable(MessageType expected, const Message& message) {
  if (message.type != expected)
    throw ProtocolError(ProtocolError::Kind::Unexpected,
                        std::string("expected ") + name(expected) + ", got " + name(message.type));
}

void rethrowAsMalformed(MessageType type) {
  try {
    throw;
  } catch (const sg::DecodeError& e) {
    throw ProtocolError(ProtocolError::Kind::Malformed, std::string(name(type)) + ": " + e.what());
  }
}

}  // namespace tsr::cluster
