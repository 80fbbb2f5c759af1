#pragma once
// Which cache key a file had the last time its bytes were hashed, found by
// the file's stamp (device, inode, size, modification time) instead of by
// reading it again: the 1.7 GB of the 50 M plant's .glb take over a second
// to map and hash, longer than the rest of a load from the cache. As
// ccache's direct mode does, a stamp is recorded only for a file last
// modified at least two seconds before it was hashed and unchanged while
// it was, so a write inside the file system's timestamp granularity cannot
// go unseen; any other change of the file changes its stamp. The entry a
// key names is still checked whole when it is read.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "tsr/sg/import/importer.hpp"

namespace tsr::sg::cache {

struct FileStamp {
  std::uint64_t device = 0, inode = 0, size = 0;
  std::int64_t modifiedNs = 0;
  bool operator==(const FileStamp&) const = default;
  // Nothing when the file cannot be stat'ed.
  static std::optional<FileStamp> of(const std::string& path);
};

// The key recorded for `source` with these options, when its stamp is `now`.
std::optional<std::string> recordedKey(const std::filesystem::path& dir, const std::string& source,
                                       const ImportOptions& options, const FileStamp& now);
// Records `key` for `source`, hashed with stamp `hashed` (taken before the
// hash), unless the file changed since or was modified too recently.
void recordKey(const std::filesystem::path& dir, const std::string& source, const ImportOptions& options,
               const FileStamp& hashed, const std::string& key);

}  // namespace tsr::sg::cache
