#pragma once
// The one error the importer throws for anything wrong with its input: a
// file that cannot be read, malformed glTF, an unknown built-in scene.
#include <stdexcept>
#include <string>

namespace tsr::sg {

class ImportError : public std::runtime_error {
 public:
  ImportError(const std::string& source, const std::string& reason)
      : std::runtime_error(source + ": " + reason), source_(source), reason_(reason) {}
  const std::string& source() const { return source_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string source_;
  std::string reason_;
};

}  // namespace tsr::sg
