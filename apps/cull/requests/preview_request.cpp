#include "requests/preview_request.hpp"

#include <nlohmann/json.hpp>

#include "requests/cull_request.hpp"

namespace tsr::app {

PreviewRequest parsePreviewRequest(const std::string& text) {
  using nlohmann::json;
  const json j = json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw CullRequestError("the message is not a JSON object");
  for (const auto& [key, value] : j.items())
    if (key != "seq" && key != "view" && key != "stop")
      throw CullRequestError("unknown field '" + key + "' (fields: seq, view, stop)");
  PreviewRequest r;
  if (!j.contains("seq") || !j["seq"].is_number_unsigned() || j["seq"].get<std::uint64_t>() > 0xffffffffu)
    throw CullRequestError("seq: expected an integer from 0 to 4294967295");
  r.seq = j["seq"].get<std::uint32_t>();
  if (j.contains("view") == j.contains("stop")) throw CullRequestError("expected either view or stop");
  if (j.contains("view")) {
    if (!j["view"].is_object()) throw CullRequestError("view: expected an object");
    r.view = parseCullRequest(j["view"].dump(), 1);
  }
  return r;
}

void checkPreviewSize(const CullQuery& view, std::uint64_t maxPixels) {
  if (std::uint64_t(view.width) * view.height > maxPixels)
    throw CullRequestError("view of " + std::to_string(view.width) + "x" + std::to_string(view.height) +
                           " pixels: previews take at most " + std::to_string(maxPixels));
}

}  // namespace tsr::app
