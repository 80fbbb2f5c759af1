#pragma once
// An array field's elements, immutable once shared: the scene, the change
// lists it commits and the replicas that apply them hold one copy of bulk
// geometry between them. The first edit after the elements were handed out
// copies them (copy on write), so the scene's own later edits never reach a
// list already built or a replica on another thread. Whether they were
// handed out is this owner's flag, not the pointer's use count: the count
// would need an acquire fence against the other thread's release, and no
// edit would save more than the one copy either way. Elements another owner
// keeps (a mapped cache entry's) are copied before their first edit too.
#include <atomic>
#include <cstddef>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "tsr/sg/array_elements.hpp"

namespace tsr::sg {

template <class E>
class SharedArray {
 public:
  using Elements = std::vector<E>;  // what a setter takes
  using Held = ArrayElements<E>;

  SharedArray() = default;
  explicit SharedArray(Elements elements) {
    // Held for the scene's life, so no room to grow: an array built by
    // appending carries up to twice its size (a third of a generated plant's
    // scene memory was this slack).
    elements.shrink_to_fit();
    if (!elements.empty()) elements_ = std::make_shared<Held>(std::move(elements));
  }
  // Elements another owner holds.
  explicit SharedArray(std::shared_ptr<const Held> elements) : elements_(std::move(elements)), handedOut_(true) {
    if (elements_ && elements_->empty()) elements_.reset();
  }
  SharedArray(SharedArray&& o) noexcept : elements_(std::move(o.elements_)), handedOut_(o.handedOut_.load()) {}
  SharedArray& operator=(SharedArray&& o) noexcept {
    elements_ = std::move(o.elements_);
    handedOut_ = o.handedOut_.load();
    return *this;
  }
  SharedArray(const SharedArray&) = delete;
  SharedArray& operator=(const SharedArray&) = delete;

  const Held& get() const { return elements_ ? *elements_ : none(); }
  std::size_t size() const { return elements_ ? elements_->size() : 0; }
  bool empty() const { return size() == 0; }
  const E* data() const { return get().data(); }

  // The elements, to be held by another owner too (null when empty).
  const std::shared_ptr<const Held>& shared() const {
    handedOut_.store(true, std::memory_order_relaxed);  // const readers may share at once (snapshots)
    return elements_;
  }

  // The elements to overwrite in place (their number is fixed): a copy of
  // them first when they were handed out or are another owner's memory.
  std::span<E> writable() {
    if (!elements_) return {};
    if (handedOut_.load(std::memory_order_relaxed) || !elements_->owned()) {
      elements_ = std::make_shared<Held>(elements_->toVector());
      handedOut_.store(false, std::memory_order_relaxed);
    }
    // Made non-const just above or by the constructor from a vector, and
    // never handed out since: editing it is defined and seen by no one else.
    return const_cast<Held&>(*elements_).writableOwn();
  }

  friend bool operator==(const SharedArray& a, const SharedArray& b) { return a.get() == b.get(); }

 private:
  static const Held& none() {
    static const Held nothing;
    return nothing;
  }
  std::shared_ptr<const Held> elements_;
  // Written by const sharers, read by the owner's edits; the owner's thread
  // orders its own edits after its own sharing, so relaxed is enough.
  mutable std::atomic<bool> handedOut_{false};
};

}  // namespace tsr::sg
