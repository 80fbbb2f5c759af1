#pragma once
// The web client's files, served by tessera-cull: "/" is web/index.html,
// "/src/..." the page's modules, "/three/..." three.js as npm installed it
// (web/node_modules/three). Only plain names under those roots, of the
// kinds a page loads, are served; anything else is refused before the
// file system is asked.
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace tsr::app {

class WebPathError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct WebFile {
  std::string body;
  std::string contentType;
};

class WebFiles {
 public:
  static constexpr std::size_t kMaxPathBytes = 256;
  static constexpr std::uintmax_t kMaxFileBytes = 16u << 20;

  explicit WebFiles(std::filesystem::path root) : root_(std::move(root)) {}
  // The file a request target names; nothing when it names none that
  // exists. Throws WebPathError for a target no file could have.
  std::optional<WebFile> get(std::string_view target) const;
  // Why the page cannot work here (no web/ or no three.js), or empty.
  std::string missing() const;

 private:
  std::filesystem::path root_;
};

}  // namespace tsr::app
