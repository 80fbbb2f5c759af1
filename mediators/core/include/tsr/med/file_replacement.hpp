#pragma once
// Writes a file so that readers see either the old file or the whole new
// one, never a partial write: the writer fills a temporary file beside the
// target (same folder, same extension, so format-by-extension writers pick
// the same format), which then replaces the target by rename. When the
// writer throws, the temporary file is removed and the target is untouched.
#include <functional>
#include <string>

namespace tsr::med {

// The temporary name used for `path`: ".<stem>.tmp-<pid><extension>" beside it.
std::string temporaryPathFor(const std::string& path);

// Calls write(temporaryPath), then renames it over `path`. Rethrows what
// write throws; throws std::runtime_error naming `path` when the rename fails.
void replaceFile(const std::string& path, const std::function<void(const std::string& temporaryPath)>& write);

// A text file written the same way (JSON outputs of the programs).
void replaceTextFile(const std::string& path, const std::string& text);

}  // namespace tsr::med
