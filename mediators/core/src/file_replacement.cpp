#include "tsr/med/file_replacement.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace tsr::med {

namespace fs = std::filesystem;

std::string temporaryPathFor(const std::string& path) {
  const fs::path p(path);
  return (p.parent_path() / ("." + p.stem().string() + ".tmp-" + std::to_string(::getpid()) + p.extension().string()))
      .string();
}

void replaceFile(const std::string& path, const std::function<void(const std::string&)>& write) {
  const std::string temporary = temporaryPathFor(path);
  std::error_code ec;
  try {
    write(temporary);
  } catch (...) {
    fs::remove(temporary, ec);
    throw;
  }
  fs::rename(temporary, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw std::runtime_error(path + ": cannot write (" + ec.message() + ")");
  }
}

void replaceTextFile(const std::string& path, const std::string& text) {
  replaceFile(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw std::runtime_error(path + ": cannot write");
  });
}

}  // namespace tsr::med
