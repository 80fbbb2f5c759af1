#pragma once
// Camera bookmarks kept beside the scene as a small JSON file
// (scene.gltf -> scene.gltf.bookmarks.json; builtin:NAME ->
// builtin-NAME.bookmarks.json in the current folder), read when the scene
// opens and rewritten (atomically) when one is saved:
//   {"version": 1, "bookmarks": [{"name": "door", "target": [0, 1, 0],
//     "distance": 3.5, "yaw": 20, "pitch": -10}]}
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace tsr::app {

class BookmarkError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Bookmark {
  std::string name;
  glm::vec3 target{0.0f};
  float distance = 1.0f;
  float yaw = 0.0f, pitch = 0.0f;  // degrees
};

struct BookmarkFile {
  std::string path;
  std::vector<Bookmark> bookmarks;
  // Why the file at `path` could not be loaded, when it could not: save()
  // then refuses, so a person's file with one typo is not replaced.
  std::string loadError;

  static std::string pathFor(const std::string& scene);
  // No file: no bookmarks. Throws BookmarkError "PATH: what is wrong" for a
  // file that is too large (64 KiB), not JSON, or holds bad values; nothing
  // is changed then.
  void load(const std::string& bookmarkPath);
  // Adds or replaces `bookmark` by name, then writes the file. Throws
  // BookmarkError (the list is unchanged then), also after a failed load.
  void save(const Bookmark& bookmark);
  const Bookmark* find(const std::string& name) const;
};

// Parses the JSON text; throws BookmarkError naming `source`.
std::vector<Bookmark> parseBookmarks(const std::string& text, const std::string& source);
std::string formatBookmarks(const std::vector<Bookmark>& bookmarks);

}  // namespace tsr::app
