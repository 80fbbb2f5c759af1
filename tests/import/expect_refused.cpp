#include "expect_refused.hpp"

#include <gtest/gtest.h>

#include "tsr/sg/import/import_error.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::test {

void expectRefused(const std::string& path, const std::string& problem, const std::string& where) {
  sg::Scene scene;
  try {
    sg::importScene(scene, path);
    ADD_FAILURE() << path << " was accepted; expected: " << problem;
  } catch (const sg::ImportError& e) {
    EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << "names where: " << e.what();
  }
  EXPECT_EQ(scene.size(), 0u) << "nothing half-imported";
}

}  // namespace tsr::test
