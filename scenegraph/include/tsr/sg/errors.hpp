#pragma once
// Typed errors of the scene graph layer. Each says what went wrong in words
// a person can act on; decode errors also say where.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace tsr::sg {

// Malformed bytes: wire messages and serialised field values.
class DecodeError : public std::runtime_error {
 public:
  DecodeError(std::size_t offset, const std::string& reason)
      : std::runtime_error("byte " + std::to_string(offset) + ": " + reason), offset_(offset), reason_(reason) {}
  std::size_t offset() const { return offset_; }
  const std::string& reason() const { return reason_; }

 private:
  std::size_t offset_;
  std::string reason_;
};

// A well-formed change list that does not fit the replica it is applied to
// (wrong version, unknown ids, references of the wrong type, cycles). The
// replica is left exactly as it was.
class ApplyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Misuse of the editing API (a cycle through children, a reference to a
// container of the wrong type or of another scene).
class SceneError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

}  // namespace tsr::sg
