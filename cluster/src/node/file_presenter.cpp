#include <spdlog/spdlog.h>

#include "tsr/cluster/presenter.hpp"
#include "tsr/med/file_replacement.hpp"
#include "tsr/med/image_file.hpp"

namespace tsr::cluster {

namespace {

class FilePresenter : public Presenter {
 public:
  FilePresenter(std::string directory, std::string node) : directory_(std::move(directory)), node_(std::move(node)) {}

  void present(std::uint64_t frame, const std::vector<PresentedTile>& tiles,
               const std::optional<WindowPlacement>&) override {
    for (const auto& [rect, image] : tiles) {
      std::string path = directory_ + "/" + node_ + "-frame" + std::to_string(frame) + "-" + std::to_string(rect.x0) +
                         "-" + std::to_string(rect.y0) + ".exr";
      try {
        // Captured by name: clang 14 (clang-tidy, the fuzz build) cannot capture a structured binding.
        med::replaceFile(path,
                         [&, &pixels = image](const std::string& temporary) { med::writeImage(temporary, pixels); });
      } catch (const std::exception& e) {
        spdlog::error("cannot present to {}: {}", path, e.what());
      }
    }
  }

 private:
  std::string directory_, node_;
};

}  // namespace

std::shared_ptr<Presenter> makeFilePresenter(std::string directory, std::string nodeName) {
  return std::make_shared<FilePresenter>(std::move(directory), std::move(nodeName));
}

}  // namespace tsr::cluster
