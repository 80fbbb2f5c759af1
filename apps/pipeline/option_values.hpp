#pragma once
// Values the programs read from their command lines and name outputs by.
#include <cstdint>
#include <string>

#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/types.hpp"

namespace tsr::app {

// "1,2.5,-3" -> a point; throws std::invalid_argument naming `option`.
sg::Vec3 parsePoint(const std::string& option, const std::string& text);
// "0,0.5" -> the shutter's open and close (range checked by
// sg::validate(LookOverride)); throws std::invalid_argument naming --shutter.
sg::Vec2 parseShutter(const std::string& text);

// "640x480" -> width, height; throws std::invalid_argument.
void parseSize(const std::string& text, std::uint32_t& width, std::uint32_t& height);

// The option that raises the import limit an error names, for its message.
std::string importLimitOption(const sg::ImportLimitError& e);

// out.png + "albedo" -> out.albedo.png
std::string aovPath(const std::string& output, const std::string& aov);

}  // namespace tsr::app
