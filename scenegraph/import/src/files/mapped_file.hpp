#pragma once
// A file's bytes mapped read-only into memory, faulted in at once: a large
// scene file or cache entry is read by the page cache without a copy in the
// heap (reading one into a vector zeroed it first and then copied it, which
// took most of a cached 50 M-triangle load).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>

namespace tsr::sg {

class MappedFile {
 public:
  MappedFile() = default;
  // Throws std::system_error when the file cannot be opened, sized or mapped.
  explicit MappedFile(const std::filesystem::path& path);
  ~MappedFile();
  MappedFile(MappedFile&& o) noexcept;
  MappedFile& operator=(MappedFile&& o) noexcept;
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  std::span<const std::uint8_t> bytes() const { return {static_cast<const std::uint8_t*>(data_), size_}; }
  // Whether only this user can rewrite the file, on a local file system:
  // then its pages change under a reader only by the user's own hand.
  // (Pages of a private mapping that were never written show later writes
  // to the file, so what was validated in another's file could change.)
  bool stable() const { return stable_; }

 private:
  void* data_ = nullptr;
  std::size_t size_ = 0;
  bool stable_ = false;
};

}  // namespace tsr::sg
