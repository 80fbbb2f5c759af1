#pragma once
// The codecs that message fields are declared with (message_fields.hpp):
// each writes one value and reads it back from hostile bytes, checking the
// bounds it was declared with and throwing sg::DecodeError with the byte
// offset of what is wrong. Reading never allocates from a count before the
// count was checked against its bound and against the bytes that remain.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "tsr/cluster/message_fields.hpp"
#include "tsr/med/parameters.hpp"
#include "tsr/med/view.hpp"
#include "tsr/sg/errors.hpp"

namespace tsr::cluster {

namespace codec {

// A varint that must not exceed `max` (nor the field's type).
struct Varint {
  std::uint64_t max;
  template <class T>
  void write(sg::ByteWriter& w, const T& v) const {
    w.varint(v);
  }
  template <class T, class Owner>
  void read(sg::ByteReader& r, T& v, const char* what, const Owner&) const {
    static_assert(std::is_unsigned_v<T>);
    const std::uint64_t limit = std::min<std::uint64_t>(max, std::numeric_limits<T>::max());
    std::size_t at = r.offset();
    std::uint64_t x = r.varint();
    if (x > limit)
      throw sg::DecodeError(at, std::string(what) + " " + std::to_string(x) + " exceeds " + std::to_string(limit));
    v = static_cast<T>(x);
  }
};

// A zigzag varint within [min, max].
struct SVarint {
  std::int64_t min, max;
  template <class T>
  void write(sg::ByteWriter& w, const T& v) const {
    w.svarint(v);
  }
  template <class T, class Owner>
  void read(sg::ByteReader& r, T& v, const char* what, const Owner&) const {
    static_assert(std::is_signed_v<T>);
    const std::int64_t lo = std::max<std::int64_t>(min, std::numeric_limits<T>::min());
    const std::int64_t hi = std::min<std::int64_t>(max, std::numeric_limits<T>::max());
    std::size_t at = r.offset();
    std::int64_t x = r.svarint();
    if (x < lo || x > hi)
      throw sg::DecodeError(at, std::string(what) + " " + std::to_string(x) + " outside [" + std::to_string(lo) + ", " +
                                    std::to_string(hi) + "]");
    v = static_cast<T>(x);
  }
};

// One byte taken as it is.
struct Byte {
  void write(sg::ByteWriter& w, std::uint8_t v) const { w.u8(v); }
  template <class Owner>
  void read(sg::ByteReader& r, std::uint8_t& v, const char*, const Owner&) const {
    v = r.u8();
  }
};

// A bool as one byte, 0 or 1.
struct Flag {
  void write(sg::ByteWriter& w, bool v) const { w.u8(v ? 1 : 0); }
  template <class Owner>
  void read(sg::ByteReader& r, bool& v, const char* what, const Owner&) const {
    std::size_t at = r.offset();
    std::uint8_t b = r.u8();
    if (b > 1) throw sg::DecodeError(at, std::string(what) + " not 0 or 1");
    v = b == 1;
  }
};

// An enum as one byte, at most `last`.
template <class E>
struct Enum {
  E last;
  void write(sg::ByteWriter& w, E v) const { w.u8(static_cast<std::uint8_t>(v)); }
  template <class Owner>
  void read(sg::ByteReader& r, E& v, const char* what, const Owner&) const {
    static_assert(sizeof(E) == 1);
    std::size_t at = r.offset();
    std::uint8_t c = r.u8();
    if (c > static_cast<std::uint8_t>(last))
      throw sg::DecodeError(at, std::string("unknown ") + what + " " + std::to_string(c));
    v = static_cast<E>(c);
  }
};

// The bytes of a fixed-size value (a nonce, a digest, a hash) as they are.
struct Fixed {
  template <class T>
  void write(sg::ByteWriter& w, const T& v) const {
    static_assert(std::is_trivially_copyable_v<T>);
    w.raw(&v, sizeof v);
  }
  template <class T, class Owner>
  void read(sg::ByteReader& r, T& v, const char* what, const Owner&) const {
    r.copy(&v, sizeof v, what);
  }
};

// A string of at most maxBytes, optionally non-empty.
struct Text {
  std::size_t maxBytes;
  bool nonEmpty;
  void write(sg::ByteWriter& w, const std::string& v) const { w.string(v); }
  template <class Owner>
  void read(sg::ByteReader& r, std::string& v, const char* what, const Owner&) const {
    v = r.string(maxBytes);
    if (nonEmpty && v.empty()) r.fail(std::string("empty ") + what);
  }
};

// A duration in seconds: a finite, non-negative double.
struct Seconds {
  void write(sg::ByteWriter& w, double v) const { w.f64(v); }
  template <class Owner>
  void read(sg::ByteReader& r, double& v, const char*, const Owner&) const {
    std::size_t at = r.offset();
    v = r.f64();
    if (!std::isfinite(v)) throw sg::DecodeError(at, "time not a finite number");
    if (v < 0) throw sg::DecodeError(at, "negative time");
  }
};

// An animation frame number from `lowest` (-1: none) to `max`, sent as the
// varint value - lowest.
struct AnimationFrame {
  std::int64_t lowest;
  std::uint64_t max;
  void write(sg::ByteWriter& w, std::int64_t v) const { w.varint(static_cast<std::uint64_t>(v - lowest)); }
  template <class Owner>
  void read(sg::ByteReader& r, std::int64_t& v, const char* what, const Owner&) const {
    std::size_t at = r.offset();
    std::uint64_t x = r.varint();
    if (x > max)
      throw sg::DecodeError(at, std::string(what) + " " + std::to_string(x) + " exceeds " + std::to_string(max));
    v = static_cast<std::int64_t>(x) + lowest;
  }
};

// The rest of the payload as bytes (change lists, pixels: their own decoders
// check them); it must be the last field. Refused when not empty while
// `mustBeEmpty` holds for what was read before it.
template <class Owner>
struct Rest {
  bool (*mustBeEmpty)(const Owner&) = nullptr;
  const char* whyEmpty = nullptr;
  void write(sg::ByteWriter& w, const std::vector<std::uint8_t>& v) const { w.raw(v.data(), v.size()); }
  void read(sg::ByteReader& r, std::vector<std::uint8_t>& v, const char* what, const Owner& partial) const {
    if (mustBeEmpty && mustBeEmpty(partial) && r.remaining() != 0) r.fail(whyEmpty);
    auto rest = r.take(r.remaining(), what);
    v.assign(rest.begin(), rest.end());
  }
};

// Pixel rectangles and views: coordinates at most maxSide, a rectangle of
// at most maxPixels (one tile's result must fit a RenderTile).
struct RectLimits {
  std::uint32_t maxSide;
  std::uint64_t maxPixels;
};
void writeRect(sg::ByteWriter& w, const med::PixelRect& rect);
// A non-empty rectangle inside a width x height image.
med::PixelRect readRect(sg::ByteReader& r, std::uint32_t width, std::uint32_t height, RectLimits limits);
void writeView(sg::ByteWriter& w, const med::View& v);
// A view that validates (med::View::validate), its region inside the image.
med::View readView(sg::ByteReader& r, RectLimits limits);
void writeParameters(sg::ByteWriter& w, const med::Parameters& p);
med::Parameters readParameters(sg::ByteReader& r, std::size_t maxCount, std::size_t maxNameBytes,
                               std::size_t maxStringBytes);

// A rectangle inside an image of limits.maxSide on each side.
struct Rect {
  RectLimits limits;
  void write(sg::ByteWriter& w, const med::PixelRect& v) const { writeRect(w, v); }
  template <class Owner>
  void read(sg::ByteReader& r, med::PixelRect& v, const char*, const Owner&) const {
    v = readRect(r, limits.maxSide, limits.maxSide, limits);
  }
};

// A rectangle inside the image of a view read before it.
template <class Owner>
struct RectInView {
  med::View Owner::*view;
  RectLimits limits;
  void write(sg::ByteWriter& w, const med::PixelRect& v) const { writeRect(w, v); }
  void read(sg::ByteReader& r, med::PixelRect& v, const char*, const Owner& partial) const {
    const med::View& image = partial.*view;
    v = readRect(r, image.width, image.height, limits);
  }
};

struct View {
  RectLimits limits;
  void write(sg::ByteWriter& w, const med::View& v) const { writeView(w, v); }
  template <class Owner>
  void read(sg::ByteReader& r, med::View& v, const char*, const Owner&) const {
    v = readView(r, limits);
  }
};

struct Parameters {
  std::size_t maxCount, maxNameBytes, maxStringBytes;
  void write(sg::ByteWriter& w, const med::Parameters& p) const { writeParameters(w, p); }
  template <class Owner>
  void read(sg::ByteReader& r, med::Parameters& p, const char*, const Owner&) const {
    p = readParameters(r, maxCount, maxNameBytes, maxStringBytes);
  }
};

// A struct that declares its own fields.
struct Nested {
  template <DeclaresFields T>
  void write(sg::ByteWriter& w, const T& v) const {
    writeFields(w, v);
  }
  template <DeclaresFields T, class Owner>
  void read(sg::ByteReader& r, T& v, const char*, const Owner&) const {
    readFields(r, v);
  }
};

// A flag byte (0 or 1), then the value when it is 1.
template <class Inner>
struct Optional {
  Inner inner;
  template <class T>
  void write(sg::ByteWriter& w, const std::optional<T>& v) const {
    w.u8(v ? 1 : 0);
    if (v) inner.write(w, *v);
  }
  template <class T, class Owner>
  void read(sg::ByteReader& r, std::optional<T>& v, const char* what, const Owner& partial) const {
    std::size_t at = r.offset();
    std::uint8_t has = r.u8();
    if (has > 1) throw sg::DecodeError(at, std::string(what) + " flag must be 0 or 1");
    v.reset();
    if (has) inner.read(r, v.emplace(), what, partial);
  }
};

// Which elements of a list must differ: none, the elements themselves, or
// one member of each.
struct AnyElements {};
struct DistinctElements {};
template <class E, class K>
struct DistinctBy {
  K E::*member;
  const char* label;
};

namespace detail {
template <class T>
std::string describe(const T& v) {
  if constexpr (std::is_convertible_v<const T&, std::string>)
    return "'" + std::string(v) + "'";
  else
    return std::to_string(v);
}
}  // namespace detail

// A count of at most `max` elements, each at least minElementBytes long,
// then the elements. `what` names one element ("viewport", "rectangle").
template <class Elem, class Distinct = AnyElements>
struct List {
  std::size_t max, minElementBytes;
  Elem elem;
  Distinct distinct = {};
  template <class T>
  void write(sg::ByteWriter& w, const std::vector<T>& v) const {
    w.varint(v.size());
    for (const T& e : v) elem.write(w, e);
  }
  template <class T, class Owner>
  void read(sg::ByteReader& r, std::vector<T>& v, const char* what, const Owner& partial) const {
    std::size_t n = r.count(max, minElementBytes, what);
    v.clear();
    v.reserve(n);  // bounded by the bytes that remain
    for (std::size_t i = 0; i < n; ++i) {
      std::size_t at = r.offset();
      elem.read(r, v.emplace_back(), what, partial);
      const T& added = v.back();
      if constexpr (std::is_same_v<Distinct, DistinctElements>) {
        if (std::count(v.begin(), v.end() - 1, added) != 0)
          r.fail(std::string(what) + " " + detail::describe(added) + " given twice");
      } else if constexpr (!std::is_same_v<Distinct, AnyElements>) {
        const auto& key = added.*distinct.member;
        for (auto e = v.begin(); e != v.end() - 1; ++e)
          if ((*e).*distinct.member == key)
            throw sg::DecodeError(at, std::string(distinct.label) + " " + detail::describe(key) + " given twice");
      }
    }
  }
};

}  // namespace codec

// The builders that fields() declarations use: wire::varint(), wire::view(...).
// (A namespace, because members are often named like their codec.)
namespace wire {
constexpr codec::Varint varint(std::uint64_t max = std::numeric_limits<std::uint64_t>::max()) { return {max}; }
constexpr codec::SVarint svarint(std::int64_t min, std::int64_t max) { return {min, max}; }
constexpr codec::Byte byte() { return {}; }
constexpr codec::Flag flag() { return {}; }
template <class E>
constexpr codec::Enum<E> enumUpTo(E last) {
  return {last};
}
constexpr codec::Fixed fixedBytes() { return {}; }
constexpr codec::Text text(std::size_t maxBytes) { return {maxBytes, false}; }
constexpr codec::Text nonEmptyText(std::size_t maxBytes) { return {maxBytes, true}; }
constexpr codec::Seconds seconds() { return {}; }
constexpr codec::AnimationFrame animationFrame(std::int64_t lowest, std::uint64_t max) { return {lowest, max}; }
template <class Owner>
constexpr codec::Rest<Owner> rest() {
  return {};
}
template <class Owner>
constexpr codec::Rest<Owner> restEmptyWhen(bool (*mustBeEmpty)(const Owner&), const char* why) {
  return {mustBeEmpty, why};
}
constexpr codec::Rect rect(std::uint32_t maxSide, std::uint64_t maxPixels) { return {{maxSide, maxPixels}}; }
template <class Owner>
constexpr codec::RectInView<Owner> rectIn(med::View Owner::*view, std::uint32_t maxSide, std::uint64_t maxPixels) {
  return {view, {maxSide, maxPixels}};
}
constexpr codec::View view(std::uint32_t maxSide, std::uint64_t maxRegionPixels) {
  return {{maxSide, maxRegionPixels}};
}
constexpr codec::Parameters parameters(std::size_t maxCount, std::size_t maxNameBytes, std::size_t maxStringBytes) {
  return {maxCount, maxNameBytes, maxStringBytes};
}
constexpr codec::Nested nested() { return {}; }
template <class Inner>
constexpr codec::Optional<Inner> optionalOf(Inner inner) {
  return {inner};
}
template <class Elem>
constexpr codec::List<Elem> listOf(std::size_t max, std::size_t minElementBytes, Elem elem) {
  return {max, minElementBytes, elem};
}
template <class Elem>
constexpr codec::List<Elem, codec::DistinctElements> distinctListOf(std::size_t max, std::size_t minElementBytes,
                                                                    Elem elem) {
  return {max, minElementBytes, elem, {}};
}
template <class Elem, class E, class K>
constexpr codec::List<Elem, codec::DistinctBy<E, K>> listOf(std::size_t max, std::size_t minElementBytes, Elem elem,
                                                            K E::*distinctMember, const char* label) {
  return {max, minElementBytes, elem, {distinctMember, label}};
}
}  // namespace wire

}  // namespace tsr::cluster
