#pragma once
// How a message (or a struct inside one) declares its fields once: a static
// constexpr fields() tuple of field(name, member, codec), in wire order, in
// the way scene graph containers list theirs with fieldSpecs(). Writing and
// reading are generated from that tuple; the codecs (field_codecs.hpp) carry
// the bounds, and every read validates what it decodes, so a decoded
// message is always well formed.
//
//   struct Swap {
//     std::uint64_t frame = 0;
//     static constexpr auto fields() { return std::tuple{field("frame", &Swap::frame, varint())}; }
//   };
//
// A codec is a small value with
//   void write(sg::ByteWriter&, const T&) const;
//   void read(sg::ByteReader&, T&, const char* what, const Owner& partial) const;
// where `what` is the field's name for error messages and `partial` the
// struct being read, its earlier fields already set (a rectangle checks
// itself against the view before it).
#include <tuple>
#include <utility>

#include "tsr/sg/wire/byte_reader.hpp"
#include "tsr/sg/wire/byte_writer.hpp"

namespace tsr::cluster {

template <class Owner, class T, class Codec>
struct MessageField {
  const char* name;
  T Owner::*member;
  Codec codec;
};

template <class Owner, class T, class Codec>
constexpr MessageField<Owner, T, Codec> field(const char* name, T Owner::*member, Codec codec) {
  return {name, member, codec};
}

// A struct that declares its fields.
template <class T>
concept DeclaresFields = requires {
  T::fields();
};

template <DeclaresFields T>
void writeFields(sg::ByteWriter& w, const T& value) {
  static constexpr auto specs = T::fields();
  std::apply([&](const auto&... f) { (f.codec.write(w, value.*f.member), ...); }, specs);
}

// Reads the fields into `value` in their order; throws sg::DecodeError with
// the byte offset of what is wrong.
template <DeclaresFields T>
void readFields(sg::ByteReader& r, T& value) {
  static constexpr auto specs = T::fields();
  std::apply([&](const auto&... f) { (f.codec.read(r, value.*f.member, f.name, std::as_const(value)), ...); }, specs);
}

}  // namespace tsr::cluster
