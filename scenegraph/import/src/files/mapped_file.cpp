#include "files/mapped_file.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/vfs.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>
#include <utility>

namespace tsr::sg {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const char* what) {
  const int error = errno;  // before anything below may change it
  throw std::system_error(error, std::generic_category(), std::string(what) + " '" + path.string() + "'");
}

// Local file systems, whose pages no other machine rewrites (network and
// FUSE file systems are left out: their files can change, or vanish, under
// a mapping).
bool localFileSystem(int fd) {
  struct statfs fs {};
  if (::fstatfs(fd, &fs) != 0) return false;
  constexpr long kLocal[] = {0xEF53 /* ext2-4 */,
                             0x58465342 /* xfs */,
                             0x9123683E /* btrfs */,
                             0x01021994 /* tmpfs */,
                             0x794C7630 /* overlay */,
                             0x2FC12FC1 /* zfs */,
                             0xF2F52010 /* f2fs */};
  for (long magic : kLocal)
    if (static_cast<long>(fs.f_type) == magic) return true;
  return false;
}

}  // namespace

MappedFile::MappedFile(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail(path, "cannot open");
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int e = errno;
    ::close(fd);
    errno = e;
    fail(path, "cannot read the size of");
  }
  size_ = static_cast<std::size_t>(st.st_size);
  stable_ = st.st_uid == ::geteuid() && (st.st_mode & (S_IWGRP | S_IWOTH)) == 0 && localFileSystem(fd);
  if (size_ > 0) {
    // Populated up front: one pass of the kernel instead of a fault a page.
    data_ = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
    if (data_ == MAP_FAILED) {
      const int e = errno;
      data_ = nullptr;
      size_ = 0;
      ::close(fd);
      errno = e;
      fail(path, "cannot map");
    }
  }
  ::close(fd);  // the mapping keeps the file
}

MappedFile::~MappedFile() {
  if (data_) ::munmap(data_, size_);
}

MappedFile::MappedFile(MappedFile&& o) noexcept
    : data_(std::exchange(o.data_, nullptr)),
      size_(std::exchange(o.size_, 0)),
      stable_(std::exchange(o.stable_, false)) {}

MappedFile& MappedFile::operator=(MappedFile&& o) noexcept {
  if (this != &o) {
    if (data_) ::munmap(data_, size_);
    data_ = std::exchange(o.data_, nullptr);
    size_ = std::exchange(o.size_, 0);
    stable_ = std::exchange(o.stable_, false);
  }
  return *this;
}

}  // namespace tsr::sg
