#pragma once
// A mesh array a back-end reads, held either as its own elements or as the
// caller's shared, immutable ones (a scene replica's arrays): a back-end
// that keeps its meshes' data for shading then holds no copy of it. Reads
// look like a vector's and cost what a vector's do (a span of the elements
// is kept); writable() copies the elements first when they are someone
// else's (copy on write), so an edit never reaches the giver. Copying a
// SharedElements copies elements it owns and shares the others.
#include <cstddef>
#include <initializer_list>
#include <memory>
#include <span>
#include <utility>
#include <vector>

namespace tsr::backend {

template <class T>
class SharedElements {
 public:
  using Elements = std::vector<T>;

  SharedElements() = default;
  SharedElements(Elements elements) { own(std::move(elements)); }
  SharedElements(std::initializer_list<T> elements) { own(Elements(elements)); }
  // Someone else's elements, held without a copy: `view` stays valid while
  // `keeper` is held (null keeper: no elements).
  SharedElements(std::span<const T> view, std::shared_ptr<const void> keeper) : elements_(std::move(keeper)) {
    if (elements_) view_ = view;
  }

  SharedElements(const SharedElements& o) {
    if (o.owned_) {
      own(Elements(o.view_.begin(), o.view_.end()));
    } else {
      elements_ = o.elements_;
      view_ = o.view_;
    }
  }
  SharedElements& operator=(const SharedElements& o) {
    if (this != &o) *this = SharedElements(o);
    return *this;
  }
  SharedElements(SharedElements&& o) noexcept
      : elements_(std::move(o.elements_)), view_(std::exchange(o.view_, {})), owned_(std::exchange(o.owned_, false)) {}
  SharedElements& operator=(SharedElements&& o) noexcept {
    elements_ = std::move(o.elements_);
    view_ = std::exchange(o.view_, {});
    owned_ = std::exchange(o.owned_, false);
    return *this;
  }

  std::size_t size() const { return view_.size(); }
  bool empty() const { return view_.empty(); }
  const T* data() const { return view_.data(); }
  const T& operator[](std::size_t i) const { return view_[i]; }
  auto begin() const { return view_.begin(); }
  auto end() const { return view_.end(); }
  operator std::span<const T>() const { return view_; }
  // Whether these elements are another owner's (held without a copy).
  bool shared() const { return elements_ && !owned_; }

  // The elements to overwrite in place (their number is fixed), copied
  // first when they are someone else's.
  std::span<T> writable() {
    if (!owned_) own(Elements(view_.begin(), view_.end()));
    // Made here, never handed out: editing it is defined and seen by no one else.
    return {const_cast<T*>(view_.data()), view_.size()};
  }

 private:
  void own(Elements elements) {
    auto made = std::make_shared<Elements>(std::move(elements));
    view_ = *made;
    elements_ = std::move(made);
    owned_ = true;
  }

  std::shared_ptr<const void> elements_;  // keeps view_'s elements
  std::span<const T> view_;
  bool owned_ = false;  // made here (edited in place) or someone else's (copied before an edit)
};

}  // namespace tsr::backend
