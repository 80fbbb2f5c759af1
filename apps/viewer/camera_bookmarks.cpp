#include "camera_bookmarks.hpp"

#include <cmath>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "text_file.hpp"
#include "tsr/med/file_replacement.hpp"

namespace tsr::app {

namespace {

constexpr std::size_t kMaxBytes = 64 * 1024;
constexpr std::size_t kMaxBookmarks = 256;
constexpr std::size_t kMaxName = 128;
constexpr float kMaxCoordinate = 1e7f;

float finite(const nlohmann::json& v, const std::string& what, float lo, float hi, const std::string& source) {
  if (!v.is_number()) throw BookmarkError(source + ": " + what + " is not a number");
  const double d = v.get<double>();
  if (!std::isfinite(d) || d < lo || d > hi)
    throw BookmarkError(source + ": " + what + " " + std::to_string(d) + " is outside " + std::to_string(lo) + " .. " +
                        std::to_string(hi));
  return static_cast<float>(d);
}

}  // namespace

std::string BookmarkFile::pathFor(const std::string& scene) {
  const std::string builtin = "builtin:";
  if (scene.rfind(builtin, 0) == 0) {
    std::string name = scene.substr(builtin.size());
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c))) c = '-';
    return "builtin-" + name + ".bookmarks.json";
  }
  return scene + ".bookmarks.json";
}

std::vector<Bookmark> parseBookmarks(const std::string& text, const std::string& source) {
  if (text.size() > kMaxBytes) throw BookmarkError(source + ": larger than 64 KiB");
  nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
  if (doc.is_discarded()) throw BookmarkError(source + ": not JSON");
  if (!doc.is_object() || !doc.contains("version") || doc["version"] != 1)
    throw BookmarkError(source + ": expected an object with \"version\": 1");
  if (!doc.contains("bookmarks") || !doc["bookmarks"].is_array())
    throw BookmarkError(source + ": expected a \"bookmarks\" array");
  if (doc["bookmarks"].size() > kMaxBookmarks) throw BookmarkError(source + ": more than 256 bookmarks");
  std::vector<Bookmark> out;
  for (std::size_t i = 0; i < doc["bookmarks"].size(); ++i) {
    const auto& b = doc["bookmarks"][i];
    const std::string at = source + ": bookmark " + std::to_string(i);
    if (!b.is_object()) throw BookmarkError(at + " is not an object");
    Bookmark m;
    if (!b.contains("name") || !b["name"].is_string()) throw BookmarkError(at + ": no \"name\" string");
    m.name = b["name"].get<std::string>();
    if (m.name.empty() || m.name.size() > kMaxName) throw BookmarkError(at + ": a name of 1 to 128 characters");
    if (!b.contains("target") || !b["target"].is_array() || b["target"].size() != 3)
      throw BookmarkError(at + ": \"target\" must be [x, y, z]");
    for (int c = 0; c < 3; ++c) m.target[c] = finite(b["target"][c], "target", -kMaxCoordinate, kMaxCoordinate, at);
    for (const char* key : {"distance", "yaw", "pitch"})
      if (!b.contains(key)) throw BookmarkError(at + ": no \"" + std::string(key) + "\"");
    m.distance = finite(b["distance"], "distance", 1e-6f, kMaxCoordinate, at);
    m.yaw = finite(b["yaw"], "yaw", -360.0f, 360.0f, at);
    m.pitch = finite(b["pitch"], "pitch", -90.0f, 90.0f, at);
    out.push_back(std::move(m));
  }
  return out;
}

std::string formatBookmarks(const std::vector<Bookmark>& bookmarks) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& b : bookmarks)
    list.push_back({{"name", b.name},
                    {"target", {b.target.x, b.target.y, b.target.z}},
                    {"distance", b.distance},
                    {"yaw", b.yaw},
                    {"pitch", b.pitch}});
  return nlohmann::json{{"version", 1}, {"bookmarks", list}}.dump(2) + "\n";
}

void BookmarkFile::load(const std::string& bookmarkPath) {
  std::vector<Bookmark> read;
  std::error_code ec;
  if (std::filesystem::exists(bookmarkPath, ec))
    read = parseBookmarks(readTextFile<BookmarkError>(bookmarkPath, kMaxBytes), bookmarkPath);
  path = bookmarkPath;
  bookmarks = std::move(read);
  loadError.clear();
}

void BookmarkFile::save(const Bookmark& bookmark) {
  if (bookmark.name.empty() || bookmark.name.size() > kMaxName)
    throw BookmarkError("a bookmark name has 1 to 128 characters");
  if (!loadError.empty())
    throw BookmarkError("not saving over " + path + ", which could not be read (" + loadError + "): fix or remove it");
  std::vector<Bookmark> next = bookmarks;
  bool replaced = false;
  for (auto& b : next)
    if (b.name == bookmark.name) {
      b = bookmark;
      replaced = true;
    }
  if (!replaced) next.push_back(bookmark);
  if (next.size() > kMaxBookmarks) throw BookmarkError(path + ": more than 256 bookmarks");
  try {
    med::replaceTextFile(path, formatBookmarks(next));
  } catch (const std::exception& e) {
    throw BookmarkError(e.what());
  }
  bookmarks = std::move(next);
}

const Bookmark* BookmarkFile::find(const std::string& name) const {
  for (const auto& b : bookmarks)
    if (b.name == name) return &b;
  return nullptr;
}

}  // namespace tsr::app
