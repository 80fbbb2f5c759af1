#pragma once
// Array elements a change list holds by reference instead of by value: the
// list's bytes carry the array's encoding and length, and the elements are
// the scene's own, shared (see SharedArray). Only lists built in this
// process hold slices; the wire codec writes their bytes in place, so a
// list read from bytes is no different from one that never had any.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <typeinfo>
#include <vector>

namespace tsr::sg {

struct SharedSlice {
  std::uint64_t offset = 0;           // where the elements' bytes would stand in the list's values
  std::shared_ptr<const void> owner;  // an ArrayElements of the element type
  const std::type_info* element = nullptr;
  const std::uint8_t* bytes = nullptr;
  std::size_t size = 0;  // in bytes
};

// In ascending offset order, as written.
using SharedSlices = std::vector<SharedSlice>;

}  // namespace tsr::sg
