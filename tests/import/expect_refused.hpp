#pragma once
// The import tests' check that a file is refused as it should be.
#include <string>

namespace tsr::test {

// Imports `path` expecting it refused: an ImportError whose message holds
// `problem` (and `where`, if given), and nothing half-imported.
void expectRefused(const std::string& path, const std::string& problem, const std::string& where = "");

}  // namespace tsr::test
