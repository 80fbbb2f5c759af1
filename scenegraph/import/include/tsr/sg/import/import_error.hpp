#pragma once
// The one error the importer throws for anything wrong with its input: a
// file that cannot be read, malformed glTF, an unknown built-in scene, an
// input over a size limit (ImportLimitError).
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

// An input refused because it is larger than an ImportOptions limit allows,
// before it was parsed. Programs name their option for raising it.
class ImportLimitError : public ImportError {
 public:
  enum class Limit { FileBytes, JsonValues };
  ImportLimitError(const std::string& source, const std::string& reason, Limit limit)
      : ImportError(source, reason), limit_(limit) {}
  Limit limit() const { return limit_; }

 private:
  Limit limit_;
};

}  // namespace tsr::sg
