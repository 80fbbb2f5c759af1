// Loads the OpenImageIO module on first use and forwards to it.
#include "tsr/imageio/image_codec.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <array>
#include <filesystem>

#include "codec_table.hpp"

namespace tsr::imageio {
namespace {

constexpr const char* kModuleName = "libtsr_imageio_oiio.so";

struct Loaded {
  const detail::CodecTable* table = nullptr;
  std::string path;   // where it was found
  std::string error;  // why not, when table is null
};

std::filesystem::path executableFolder() {
  std::array<char, 4096> buffer{};
  const ssize_t n = ::readlink("/proc/self/exe", buffer.data(), buffer.size() - 1);
  if (n <= 0) return {};
  return std::filesystem::path(std::string(buffer.data(), std::size_t(n))).parent_path();
}

// Beside an installed program first (a package can be moved), then where
// this build put it, then where this build installs it.
std::vector<std::string> candidates() {
  std::vector<std::string> out;
  if (const auto bin = executableFolder(); !bin.empty())
    out.push_back((bin.parent_path() / TSR_IMAGEIO_INSTALL_SUBDIR / kModuleName).string());
  out.emplace_back(TSR_IMAGEIO_BUILD_MODULE);
  out.emplace_back(TSR_IMAGEIO_INSTALL_MODULE);
  return out;
}

Loaded load() {
  Loaded result;
  std::string tried;
  for (const std::string& path : candidates()) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
      tried += "\n  " + path + " (absent)";
      continue;
    }
    // Never closed: OpenImageIO keeps threads and caches until exit.
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      tried += "\n  " + path + " (" + ::dlerror() + ")";
      continue;
    }
    using Entry = const detail::CodecTable* (*)();
    const auto entry = reinterpret_cast<Entry>(::dlsym(handle, TSR_IMAGEIO_ENTRY));
    if (!entry) {
      tried += "\n  " + path + " (no " TSR_IMAGEIO_ENTRY ": a module of another version)";
      continue;
    }
    result.table = entry();
    result.path = path;
    return result;
  }
  result.error = std::string("image files need ") + kModuleName + " (OpenImageIO), not found or not loadable:" + tried;
  return result;
}

const Loaded& loaded() {
  static const Loaded once = load();  // thread-safe, once
  if (!once.table) throw CodecError(once.error);
  return once;
}

const detail::CodecTable& table() { return *loaded().table; }

void raiseIf(const std::string& problem, const std::string& prefix) {
  if (!problem.empty()) throw CodecError(prefix + problem);
}

}  // namespace

void writeFile(const std::string& path, const std::string& formatName, const Layout& layout,
               std::span<const std::byte> pixels) {
  raiseIf(table().writeFile(path, formatName, layout, pixels), formatName + ": ");
}

std::vector<std::uint8_t> encode(const std::string& formatName, const Layout& layout,
                                 std::span<const std::byte> pixels) {
  std::vector<std::uint8_t> out;
  raiseIf(table().encode(formatName, layout, pixels, out), formatName + ": ");
  return out;
}

Image readFile(const std::string& path, Sample as) {
  Image out;
  raiseIf(table().readFile(path, as, out), path + " ");
  return out;
}

Image decode(std::span<const std::uint8_t> encoded, const std::string& formatName, std::uint64_t maxPixels) {
  Image out;
  raiseIf(table().decode(encoded, formatName, maxPixels, out), "");
  return out;
}

std::string modulePath() { return loaded().path; }

}  // namespace tsr::imageio
