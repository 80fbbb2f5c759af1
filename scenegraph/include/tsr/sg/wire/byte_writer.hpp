#pragma once
// Appends little-endian values and LEB128 varints to a byte vector.
#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <string_view>
#include <vector>

#include "tsr/sg/wire/shared_slices.hpp"

namespace tsr::sg {

static_assert(std::endian::native == std::endian::little,
              "the wire format is little-endian and copied as such; port the codec before using a big-endian host");

class ByteWriter {
 public:
  explicit ByteWriter(std::vector<std::uint8_t>& out) : out_(out) {}
  // A writer with a slice table writes shared arrays by reference into it
  // (a change list built in this process); without one, every byte.
  ByteWriter(std::vector<std::uint8_t>& out, SharedSlices* slices) : out_(out), slices_(slices) {}

  void u8(std::uint8_t v) { out_.push_back(v); }
  void u32(std::uint32_t v) { raw(&v, sizeof v); }
  void varint(std::uint64_t v) {
    while (v >= 0x80) {
      out_.push_back(static_cast<std::uint8_t>(v | 0x80));
      v >>= 7;
    }
    out_.push_back(static_cast<std::uint8_t>(v));
  }
  void svarint(std::int64_t v) {  // zigzag, so small negatives stay short
    varint((static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63));
  }
  void f32(float v) { raw(&v, sizeof v); }
  void f64(double v) { raw(&v, sizeof v); }
  void string(std::string_view s) {
    varint(s.size());
    raw(s.data(), s.size());
  }
  void raw(const void* data, std::size_t size) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    out_.insert(out_.end(), p, p + size);
  }
  std::size_t size() const { return out_.size(); }
  std::vector<std::uint8_t>& buffer() { return out_; }
  SharedSlices* slices() const { return slices_; }

  // Writes a 32-bit little-endian value over bytes already written.
  void patchU32(std::size_t at, std::uint32_t v) { std::memcpy(out_.data() + at, &v, sizeof v); }

 private:
  std::vector<std::uint8_t>& out_;
  SharedSlices* slices_ = nullptr;
};

}  // namespace tsr::sg
