#pragma once
// The bad inputs every program that reads them is tested with: each writes
// its files into a scratch folder and names the file argument and a phrase
// the one error line must contain.
#include <filesystem>
#include <string>
#include <vector>

namespace tsr::test {

struct BadInput {
  std::string name;   // for the test's trace
  std::string path;   // the argument, relative to the scratch folder
  std::string about;  // what the error line must name
};

// Writes the files into `dir` (a secret.bin beside the glTF folder is a valid
// buffer, so a uri that reached it would make the import succeed).
std::vector<BadInput> writeBadSceneInputs(const std::filesystem::path& dir);

// Files no --script reader (tessera-viewer's, tessera-anaglyph's) accepts,
// whatever its actions: missing, a folder, binary, too large, an unknown action.
std::vector<BadInput> writeBadScriptFiles(const std::filesystem::path& dir);

}  // namespace tsr::test
