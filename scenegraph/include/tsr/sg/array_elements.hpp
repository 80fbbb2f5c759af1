#pragma once
// The elements of one array field as a SharedArray holds them: a vector of
// its own, or memory another owner keeps alive (a converted-scene cache
// entry mapped into memory, whose arrays a cached load uses in place). Reads
// look like a const vector's; the elements never change once made.
#include <algorithm>
#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

namespace tsr::sg {

template <class E>
class ArrayElements {
 public:
  ArrayElements() = default;
  explicit ArrayElements(std::vector<E> own) : owned_(std::move(own)), view_(owned_) {}
  // `view` stays valid as long as `keeper` is held (which must not be null).
  ArrayElements(std::span<const E> view, std::shared_ptr<const void> keeper) : view_(view), keeper_(std::move(keeper)) {
    if (!keeper_) throw std::invalid_argument("ArrayElements: a view needs the owner that keeps it");
  }
  // Held by shared pointer: a copy is made on purpose (toVector), never by accident.
  ArrayElements(const ArrayElements&) = delete;
  ArrayElements& operator=(const ArrayElements&) = delete;

  std::size_t size() const { return view_.size(); }
  bool empty() const { return view_.empty(); }
  const E* data() const { return view_.data(); }
  const E& operator[](std::size_t i) const { return view_[i]; }
  const E& front() const { return view_.front(); }
  const E& back() const { return view_.back(); }
  const E* begin() const { return view_.data(); }
  const E* end() const { return view_.data() + view_.size(); }
  operator std::span<const E>() const { return view_; }
  std::vector<E> toVector() const { return {begin(), end()}; }
  // Whether the elements are this object's own (else another owner's memory).
  bool owned() const { return view_.data() == owned_.data(); }

  friend bool operator==(const ArrayElements& a, const ArrayElements& b) { return std::ranges::equal(a, b); }
  friend bool operator==(const ArrayElements& a, const std::vector<E>& b) { return std::ranges::equal(a, b); }

 private:
  template <class>
  friend class SharedArray;
  // For the SharedArray that made these elements and never handed them out.
  std::span<E> writableOwn() { return {owned_.data(), owned_.size()}; }

  std::vector<E> owned_;
  std::span<const E> view_;
  std::shared_ptr<const void> keeper_;
};

// The elements a shared pointer holds, or none.
template <class E>
std::span<const E> elementsOf(const std::shared_ptr<const ArrayElements<E>>& elements) {
  return elements ? std::span<const E>(*elements) : std::span<const E>();
}

}  // namespace tsr::sg
