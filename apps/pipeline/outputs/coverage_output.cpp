#include "outputs/coverage_output.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <string_view>

#include <nlohmann/json.hpp>

#include "tsr/med/file_replacement.hpp"

#if TSR_HAVE_COVERAGE
#include "tsr/med/coverage/ranking.hpp"
#endif

namespace tsr::app {

bool isRankingPath(const std::string& path) {
  if (path.size() < 5) return false;
  std::string ext = path.substr(path.size() - 5);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".json";
}

void writeRanking(const std::string& path, const med::FrameBuffer& image, const sg::Scene& scene) {
#if TSR_HAVE_COVERAGE
  static_assert(std::string_view(kRankingOutput) == med::kIdOutput);
  if (!image.outputs.count(med::kIdOutput))
    throw std::runtime_error(path + ": a .json ranking needs a back-end with an id output (--backend coverage)");
  nlohmann::json objects = nlohmann::json::array();
  for (const auto& o : med::rankObjects(image, scene))
    objects.push_back({{"id", o.id}, {"name", o.name}, {"pixels", o.pixels}, {"fraction", o.fraction}});
  nlohmann::json j = {{"width", image.width},
                      {"height", image.height},
                      {"background", med::backgroundPixels(image)},
                      {"objects", std::move(objects)}};
  med::replaceTextFile(path, j.dump(2) + "\n");
#else
  (void)image;
  (void)scene;
  throw std::runtime_error(path + ": a .json ranking needs the coverage back-end, which this build lacks");
#endif
}

}  // namespace tsr::app
