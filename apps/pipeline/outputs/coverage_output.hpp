#pragma once
// tessera-render's ranking output: with --output FILE.json, the objects the
// view shows ranked by the pixels they cover, read from the frame buffer's
// "id" output (the coverage back-end writes it).
#include <string>

#include "tsr/med/frame_buffer.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::app {

bool isRankingPath(const std::string& path);         // ends in .json (any case)
inline constexpr const char* kRankingOutput = "id";  // the output writeRanking reads

// Writes {"width", "height", "background", "objects": [{"id", "name",
// "pixels", "fraction"}]} sorted by pixels. Throws std::runtime_error when
// the image has no id output or the file cannot be written.
void writeRanking(const std::string& path, const med::FrameBuffer& image, const sg::Scene& scene);

}  // namespace tsr::app
