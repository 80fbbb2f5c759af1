#include <cstdlib>
#include <string>

#include "camera_bookmarks.hpp"
#include "fuzz_targets.hpp"

namespace tsr::fuzz {

// A bookmarks file; what it accepts must survive being saved and read again
// (the viewer rewrites the whole file when one bookmark is saved).
void cameraBookmarks(Bytes bytes) {
  const std::string text(bytes.begin(), bytes.end());
  std::vector<app::Bookmark> marks;
  try {
    marks = app::parseBookmarks(text, "fuzz-input");
  } catch (const app::BookmarkError&) {
    return;
  }
  const auto again = app::parseBookmarks(app::formatBookmarks(marks), "again");
  if (again.size() != marks.size()) std::abort();
  for (std::size_t i = 0; i < marks.size(); ++i)
    if (again[i].name != marks[i].name || again[i].target != marks[i].target ||
        again[i].distance != marks[i].distance || again[i].yaw != marks[i].yaw || again[i].pitch != marks[i].pitch)
      std::abort();
}

}  // namespace tsr::fuzz
