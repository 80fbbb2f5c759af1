#include "cache/stamp_index.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <fstream>

#include "cache/scene_cache.hpp"

namespace tsr::sg::cache {
namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'T', 'S', 'R', 'S', 'T', 'A', 'M', 'P'};
constexpr std::int64_t kSettledNs = 2'000'000'000;

struct Record {
  char magic[8];
  std::uint64_t device, inode, size;
  std::int64_t modifiedNs;
  char key[64];
};
static_assert(sizeof(Record) == 104);

// The record's file: named by the source's absolute path, the options and
// the importer's version (all in cache::key).
fs::path recordPath(const fs::path& dir, const std::string& source, const ImportOptions& options) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(source, ec);
  const std::string name = "stamp of " + (ec ? source : absolute.lexically_normal().string());
  return dir / (key({reinterpret_cast<const std::uint8_t*>(name.data()), name.size()}, options) + ".tsrstamp");
}

bool isKey(const char (&k)[64]) {
  for (char c : k)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;  // a path could climb out of the folder
  return true;
}

}  // namespace

std::optional<FileStamp> FileStamp::of(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
  return FileStamp{std::uint64_t(st.st_dev), std::uint64_t(st.st_ino), std::uint64_t(st.st_size),
                   std::int64_t(st.st_mtim.tv_sec) * 1'000'000'000 + st.st_mtim.tv_nsec};
}

std::optional<std::string> recordedKey(const fs::path& dir, const std::string& source, const ImportOptions& options,
                                       const FileStamp& now) {
  std::ifstream in(recordPath(dir, source, options), std::ios::binary);
  Record r{};
  if (!in.read(reinterpret_cast<char*>(&r), sizeof r) || in.peek() != std::ifstream::traits_type::eof())
    return std::nullopt;
  if (std::memcmp(r.magic, kMagic, sizeof kMagic) != 0 || !isKey(r.key)) return std::nullopt;
  if (FileStamp{r.device, r.inode, r.size, r.modifiedNs} != now) return std::nullopt;
  return std::string(r.key, sizeof r.key);
}

void recordKey(const fs::path& dir, const std::string& source, const ImportOptions& options, const FileStamp& hashed,
               const std::string& key) {
  const std::int64_t nowNs =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  if (nowNs - hashed.modifiedNs < kSettledNs || FileStamp::of(source) != hashed || key.size() != 64) return;
  Record r{};
  std::memcpy(r.magic, kMagic, sizeof kMagic);
  r.device = hashed.device, r.inode = hashed.inode, r.size = hashed.size, r.modifiedNs = hashed.modifiedNs;
  std::memcpy(r.key, key.data(), sizeof r.key);
  const fs::path path = recordPath(dir, source, options);
  const fs::path temporary = path.string() + ".tmp" + std::to_string(::getpid());
  std::error_code ec;
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(&r), sizeof r);
    out.close();
    if (!out) {
      fs::remove(temporary, ec);
      return;  // only a faster next load is lost
    }
  }
  fs::rename(temporary, path, ec);
  if (ec) fs::remove(temporary, ec);
}

}  // namespace tsr::sg::cache
