#pragma once
// The folder holding this program's executable (an install's bin/ or the
// build's), for finding what is installed or built beside it.
#include <filesystem>
#include <optional>
#include <system_error>

namespace tsr::app {

inline std::optional<std::filesystem::path> programFolder() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return std::nullopt;
  return self.parent_path();
}

}  // namespace tsr::app
