#pragma once
// Reads a small text file a person names on the command line (a script, a
// bookmarks file): bounded, and refused with a message naming the file and
// why (missing, a folder, too large) as `Error`, the caller's typed error.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace tsr::app {

template <class Error>
std::string readTextFile(const std::string& path, std::uintmax_t maxBytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (!fs::exists(status)) throw Error(path + ": no such file");
  if (fs::is_directory(status)) throw Error(path + ": it is a directory, not a file");
  if (!fs::is_regular_file(status)) throw Error(path + ": not a regular file");
  const auto size = fs::file_size(path, ec);
  if (ec) throw Error(path + ": cannot be read (" + ec.message() + ")");
  const auto limit =
      maxBytes >= (1u << 20) ? std::to_string(maxBytes >> 20) + " MiB" : std::to_string(maxBytes >> 10) + " KiB";
  if (size > maxBytes) throw Error(path + ": larger than " + limit);
  std::ifstream in(path, std::ios::binary);
  std::string text(static_cast<std::size_t>(size), '\0');
  if (!in || !in.read(text.data(), static_cast<std::streamsize>(size))) throw Error(path + ": cannot be read");
  return text;
}

}  // namespace tsr::app
