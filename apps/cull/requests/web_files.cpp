#include "requests/web_files.hpp"

#include <array>
#include <fstream>
#include <sstream>
#include <utility>

namespace tsr::app {

namespace {

constexpr std::array<std::pair<std::string_view, std::string_view>, 6> kTypes{{
    {".html", "text/html; charset=utf-8"},
    {".js", "text/javascript; charset=utf-8"},
    {".css", "text/css; charset=utf-8"},
    {".json", "application/json"},
    {".png", "image/png"},
    {".svg", "image/svg+xml"},
}};

// Names of letters, digits, '-', '_' and '.', none starting with '.', so
// no "..", no hidden files, no encoded or doubled separators.
void checkRelative(std::string_view path) {
  if (path.empty() || path.size() > WebFiles::kMaxPathBytes) throw WebPathError("path empty or too long");
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t end = std::min(path.find('/', start), path.size());
    const std::string_view name = path.substr(start, end - start);
    if (name.empty() || name.front() == '.') throw WebPathError("path with an empty or dotted name");
    for (char c : name)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.'))
        throw WebPathError("path with a character other than letters, digits, '-', '_', '.' and '/'");
    start = end + 1;
  }
}

std::string_view typeOf(std::string_view path) {
  for (const auto& [extension, type] : kTypes)
    if (path.ends_with(extension)) return type;
  throw WebPathError("not a kind of file the page loads");
}

}  // namespace

std::optional<WebFile> WebFiles::get(std::string_view target) const {
  if (const auto query = target.find('?'); query != std::string_view::npos) target = target.substr(0, query);
  std::filesystem::path file;
  if (target == "/" || target == "/index.html") {
    file = root_ / "index.html";
  } else if (target.starts_with("/src/")) {
    checkRelative(target.substr(5));
    file = root_ / "src" / std::string(target.substr(5));
  } else if (target.starts_with("/three/")) {
    checkRelative(target.substr(7));
    file = root_ / "node_modules" / "three" / std::string(target.substr(7));
  } else {
    return std::nullopt;
  }
  const std::string_view type = typeOf(file.native());
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
  const auto size = std::filesystem::file_size(file, ec);
  if (ec || size > kMaxFileBytes) return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  std::ostringstream body;
  body << in.rdbuf();
  if (!in) return std::nullopt;
  return WebFile{std::move(body).str(), std::string(type)};
}

std::string WebFiles::missing() const {
  if (!std::filesystem::is_regular_file(root_ / "index.html"))
    return "no web client in " + root_.string() + " (index.html missing)";
  if (!std::filesystem::is_regular_file(root_ / "node_modules" / "three" / "build" / "three.module.js"))
    return "three.js missing from " + (root_ / "node_modules").string() + ": run 'npm ci' in " + root_.string() +
           " (scripts/install-deps.sh does)";
  return {};
}

}  // namespace tsr::app
