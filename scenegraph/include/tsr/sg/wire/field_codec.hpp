#pragma once
// How each kind of field value is written to and read from bytes. One path
// serves commits, snapshots, the wire and the content hash (as Collage's
// serialisable does): a value written here reads back bit for bit.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "tsr/sg/array_range.hpp"
#include "tsr/sg/attachment.hpp"
#include "tsr/sg/coordinate_limit.hpp"
#include "tsr/sg/shared_array.hpp"
#include "tsr/sg/types.hpp"
#include "tsr/sg/wire/byte_reader.hpp"
#include "tsr/sg/wire/byte_writer.hpp"
#include "tsr/sg/wire/decode_limits.hpp"
#include "tsr/sg/wire/shared_slices.hpp"

namespace tsr::sg {

// What a field read needs besides the bytes. In scan mode (decoding a change
// list without a target scene) ranged array edits are checked but not
// stored, and the array length they expect is reported instead.
struct FieldReadContext {
  FieldReadContext(const DecodeLimits& l, bool scan) : limits(l), scanOnly(scan) {}
  const DecodeLimits& limits;
  bool scanOnly = false;
  // Filled when a ranged array edit was read: the array length it expects
  // and the runs it overwrote.
  bool sawRanges = false;
  std::uint64_t rangedTotal = 0;
  std::vector<ArrayRange> ranges;
  // Applying a list built in this process: its shared arrays, by offset.
  const SharedSlices* slices = nullptr;
  // Reading bytes into a list: whole arrays read into shared arrays are
  // recorded here, so the list holds them by reference.
  SharedSlices* collected = nullptr;
};

namespace codec {

enum class ArrayEncoding : std::uint8_t { Whole = 0, Ranges = 1 };

template <class T>
concept Enum = std::is_enum_v<T>;

inline void write(ByteWriter& w, bool v) { w.u8(v ? 1 : 0); }
inline void read(ByteReader& r, bool& v, FieldReadContext&) {
  std::uint8_t b = r.u8();
  if (b > 1) r.fail("boolean is " + std::to_string(b));
  v = b != 0;
}

inline void write(ByteWriter& w, std::uint32_t v) { w.varint(v); }
inline void read(ByteReader& r, std::uint32_t& v, FieldReadContext&) {
  std::uint64_t x = r.varint();
  if (x > UINT32_MAX) r.fail("value " + std::to_string(x) + " does not fit 32 bits");
  v = static_cast<std::uint32_t>(x);
}

inline void write(ByteWriter& w, std::uint64_t v) { w.varint(v); }
inline void read(ByteReader& r, std::uint64_t& v, FieldReadContext&) { v = r.varint(); }

inline void write(ByteWriter& w, float v) { w.f32(v); }
inline void read(ByteReader& r, float& v, FieldReadContext&) { v = r.f32(); }

// Enumerations end with a Count enumerator, which bounds what a read accepts.
template <Enum E>
void write(ByteWriter& w, E v) {
  w.u8(static_cast<std::uint8_t>(v));
}
template <Enum E>
void read(ByteReader& r, E& v, FieldReadContext&) {
  std::uint8_t b = r.u8();
  if (b >= static_cast<std::uint8_t>(E::Count)) r.fail("enumeration value " + std::to_string(b) + " out of range");
  v = static_cast<E>(b);
}

template <int N>
void write(ByteWriter& w, const glm::vec<N, float>& v) {
  w.raw(&v[0], sizeof(float) * N);
}
template <int N>
void read(ByteReader& r, glm::vec<N, float>& v, FieldReadContext&) {
  for (int i = 0; i < N; ++i) v[i] = r.f32();
}

inline void write(ByteWriter& w, const Mat4& m) { w.raw(&m[0][0], sizeof(float) * 16); }
// Matrices place geometry and cameras, so their entries obey kMaxCoordinate.
inline void read(ByteReader& r, Mat4& m, FieldReadContext&) {
  for (int c = 0; c < 4; ++c)
    for (int i = 0; i < 4; ++i) {
      m[c][i] = r.f32();
      if (!withinCoordinateLimit(m[c][i]))
        throw DecodeError(r.offset() - sizeof(float),
                          "matrix entry " + std::to_string(m[c][i]) + " is beyond the coordinate limit of 1e12");
    }
}

inline void write(ByteWriter& w, const std::string& s) { w.string(s); }
inline void read(ByteReader& r, std::string& s, FieldReadContext& ctx) { s = r.string(ctx.limits.maxStringBytes); }

// Reference lists (children): a count and one varint id each.
inline void write(ByteWriter& w, const std::vector<ContainerId>& ids) {
  w.varint(ids.size());
  for (ContainerId id : ids) w.varint(id);
}
inline void read(ByteReader& r, std::vector<ContainerId>& ids, FieldReadContext& ctx) {
  std::size_t n = r.count(ctx.limits.maxArrayElements, 1, "reference");
  ids.resize(n);
  for (auto& id : ids) id = r.varint();
}

void write(ByteWriter& w, const Attachments& a);
void read(ByteReader& r, Attachments& a, FieldReadContext& ctx);

// Plain-old-data array elements: copied as bytes; float ones (positions,
// normals, uvs, colours) must be finite and within kMaxCoordinate.
template <class E>
concept ArrayElement = std::is_same_v<E, std::uint8_t> || std::is_same_v<E, std::uint32_t> || std::is_same_v<E, Vec2> ||
    std::is_same_v<E, Vec3> || std::is_same_v<E, Vec4>;

template <ArrayElement E>
bool allWithinLimit(const E* data, std::size_t n) {
  if constexpr (std::is_integral_v<E>) {
    return true;
  } else {
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < E::length(); ++k)
        if (!withinCoordinateLimit(data[i][k])) return false;
    return true;
  }
}

// An array goes whole, or, when only parts of it were edited this frame,
// as its total length plus the edited runs.
template <ArrayElement E>
void writeArray(ByteWriter& w, std::span<const E> a, const std::vector<ArrayRange>* edited) {
  if (!edited) {
    w.u8(static_cast<std::uint8_t>(ArrayEncoding::Whole));
    w.varint(a.size());
    w.raw(a.data(), a.size() * sizeof(E));
    return;
  }
  w.u8(static_cast<std::uint8_t>(ArrayEncoding::Ranges));
  w.varint(a.size());
  w.varint(edited->size());
  for (const auto& range : *edited) {
    w.varint(range.begin);
    w.varint(range.size());
    w.raw(a.data() + range.begin, range.size() * sizeof(E));
  }
}
template <ArrayElement E>
void writeArray(ByteWriter& w, const std::vector<E>& a, const std::vector<ArrayRange>* edited) {
  writeArray(w, std::span<const E>(a), edited);
}

namespace detail {
// The runs of a ranged edit, after the encoding byte; stores them into
// `target` (of `size` elements) unless scanning.
template <ArrayElement E>
void readRanges(ByteReader& r, E* target, std::size_t size, FieldReadContext& ctx) {
  std::size_t totalAt = r.offset();
  std::uint64_t total = r.varint();
  if (total > ctx.limits.maxArrayElements) throw DecodeError(totalAt, "array length exceeds limit");
  if (!ctx.scanOnly && total != size)
    throw DecodeError(totalAt,
                      "ranged edit expects " + std::to_string(total) + " elements, array has " + std::to_string(size));
  ctx.sawRanges = true;
  ctx.rangedTotal = total;
  ctx.ranges.clear();
  std::size_t nRanges = r.count(ctx.limits.maxRanges, 2, "range");
  std::uint64_t previousEnd = 0;
  for (std::size_t i = 0; i < nRanges; ++i) {
    std::size_t at = r.offset();
    std::uint64_t begin = r.varint();
    std::uint64_t n = r.varint();
    if (n == 0 || begin < previousEnd || begin > total || n > total - begin)
      throw DecodeError(at, "range [" + std::to_string(begin) + ", +" + std::to_string(n) +
                                ") is empty, out of order or outside the array of " + std::to_string(total));
    previousEnd = begin + n;
    ctx.ranges.push_back({begin, begin + n});
    auto bytes = r.take(n * sizeof(E), "range data");  // n <= total <= limit, so no overflow
    if constexpr (!std::is_integral_v<E>) {
      std::vector<E> check(bytes.size() / sizeof(E));
      std::memcpy(static_cast<void*>(check.data()), bytes.data(), bytes.size());
      if (!allWithinLimit(check.data(), check.size()))
        throw DecodeError(at, "range holds a float that is not finite or beyond 1e12");
      if (!ctx.scanOnly) std::copy(check.begin(), check.end(), target + begin);
    } else if (!ctx.scanOnly) {
      std::memcpy(target + begin, bytes.data(), bytes.size());
    }
  }
}

// The elements of a whole array, after its encoding byte and its count
// (read at `countAt`).
template <ArrayElement E>
void readElements(ByteReader& r, std::vector<E>& a, std::size_t n, std::size_t countAt) {
  std::size_t at = r.offset();
  if (n > r.remaining() / sizeof(E))
    throw DecodeError(countAt, "array element count " + std::to_string(n) + " exceeds the bytes that remain");
  a.resize(n);
  r.copy(a.data(), n * sizeof(E), "array data");
  if (!allWithinLimit(a.data(), n)) throw DecodeError(at, "array holds a float that is not finite or beyond 1e12");
}

inline const SharedSlice* sliceAt(const SharedSlices* slices, std::uint64_t offset) {
  if (!slices) return nullptr;
  auto it = std::lower_bound(slices->begin(), slices->end(), offset,
                             [](const SharedSlice& s, std::uint64_t at) { return s.offset < at; });
  return it != slices->end() && it->offset == offset ? &*it : nullptr;
}
}  // namespace detail

template <ArrayElement E>
void readArray(ByteReader& r, std::vector<E>& a, FieldReadContext& ctx) {
  std::uint8_t encoding = r.u8();
  if (encoding == static_cast<std::uint8_t>(ArrayEncoding::Whole)) {
    std::size_t countAt = r.offset();
    std::size_t n = r.count(ctx.limits.maxArrayElements, 0, "array element");
    detail::readElements(r, a, n, countAt);
    return;
  }
  if (encoding != static_cast<std::uint8_t>(ArrayEncoding::Ranges))
    r.fail("unknown array encoding " + std::to_string(encoding));
  detail::readRanges(r, a.data(), a.size(), ctx);
}

// Shared arrays go by reference into a writer with a slice table.
template <ArrayElement E>
void writeArray(ByteWriter& w, const SharedArray<E>& a, const std::vector<ArrayRange>* edited) {
  if (edited || !w.slices() || a.empty()) return writeArray(w, std::span<const E>(a.get()), edited);
  w.u8(static_cast<std::uint8_t>(ArrayEncoding::Whole));
  w.varint(a.size());
  w.slices()->push_back(
      {w.size(), a.shared(), &typeid(E), reinterpret_cast<const std::uint8_t*>(a.data()), a.size() * sizeof(E)});
}

template <ArrayElement E>
void readArray(ByteReader& r, SharedArray<E>& a, FieldReadContext& ctx) {
  std::uint8_t encoding = r.u8();
  if (encoding == static_cast<std::uint8_t>(ArrayEncoding::Whole)) {
    std::size_t countAt = r.offset();
    std::size_t n = r.count(ctx.limits.maxArrayElements, 0, "array element");
    if (const SharedSlice* slice = detail::sliceAt(ctx.slices, r.offset())) {
      // A list of this process: its elements were checked when the scene took them.
      if (*slice->element != typeid(E) || slice->size != n * sizeof(E)) r.fail("shared array does not match its field");
      a = SharedArray<E>(std::static_pointer_cast<const ArrayElements<E>>(slice->owner));
      return;
    }
    std::size_t at = r.offset();
    std::vector<E> read;
    detail::readElements(r, read, n, countAt);
    auto elements = std::make_shared<const ArrayElements<E>>(std::move(read));
    if (ctx.collected && n)
      ctx.collected->push_back(
          {at, elements, &typeid(E), reinterpret_cast<const std::uint8_t*>(elements->data()), n * sizeof(E)});
    a = SharedArray<E>(std::move(elements));
    return;
  }
  if (encoding != static_cast<std::uint8_t>(ArrayEncoding::Ranges))
    r.fail("unknown array encoding " + std::to_string(encoding));
  if (ctx.scanOnly) return detail::readRanges<E>(r, nullptr, 0, ctx);
  std::size_t size = a.size();
  detail::readRanges(r, size ? a.writable().data() : nullptr, size, ctx);
}

}  // namespace codec
}  // namespace tsr::sg
