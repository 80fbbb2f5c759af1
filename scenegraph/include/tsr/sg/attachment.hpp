#pragma once
// Attachments: named extension values any container can carry. A mediator
// reads the names it understands (say "embree.maxDepth") and ignores others.
#include <cstdint>
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace tsr::sg {

using AttachmentValue = std::variant<std::int64_t, double, std::string, std::vector<float>>;
using Attachments = std::map<std::string, AttachmentValue, std::less<>>;

}  // namespace tsr::sg
