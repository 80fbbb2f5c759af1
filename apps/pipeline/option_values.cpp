#include "option_values.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

namespace tsr::app {

namespace {
constexpr std::uint64_t kMaxImagePixels = std::uint64_t{1} << 26;
}  // namespace

void parseSize(const std::string& text, std::uint32_t& width, std::uint32_t& height) {
  auto x = text.find('x');
  auto number = [&](std::string_view s) {
    std::uint32_t v = 0;
    auto [end, err] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (err != std::errc() || end != s.data() + s.size() || v == 0 || v > 32768)
      throw std::invalid_argument("--size " + text + ": expected WxH with each side 1..32768");
    return v;
  };
  if (x == std::string::npos) throw std::invalid_argument("--size " + text + ": expected WxH, e.g. 512x512");
  width = number(std::string_view(text).substr(0, x));
  height = number(std::string_view(text).substr(x + 1));
  // Colour, depth and outputs take 20+ bytes a pixel: refuse what no machine
  // here could hold before a back-end tries to allocate it.
  if (std::uint64_t{width} * height > kMaxImagePixels)
    throw std::invalid_argument("--size " + text + ": more than " + std::to_string(kMaxImagePixels) +
                                " pixels (8192x8192)");
}

namespace {
// "a,b,c" -> `count` numbers into out; throws naming `option` and `shape`.
void parseNumbers(const std::string& option, const std::string& text, float* out, int count, const std::string& shape) {
  std::size_t start = 0;
  for (int i = 0; i < count; ++i) {
    const std::size_t comma = text.find(',', start);
    if ((i < count - 1) != (comma != std::string::npos))
      throw std::invalid_argument(option + " " + text + ": expected " + shape);
    const std::string part = text.substr(start, i < count - 1 ? comma - start : std::string::npos);
    const char* begin = part.c_str();
    char* end = nullptr;
    out[i] = std::strtof(begin, &end);
    if (part.empty() || end != begin + part.size() || std::isspace(static_cast<unsigned char>(part.front())))
      throw std::invalid_argument(option + " " + text + ": '" + part + "' is not a number");
    start = comma + 1;
  }
}
}  // namespace

sg::Vec3 parsePoint(const std::string& option, const std::string& text) {
  sg::Vec3 p(0.0f);
  parseNumbers(option, text, &p[0], 3, "X,Y,Z (three numbers separated by commas)");
  return p;
}

sg::Vec2 parseShutter(const std::string& text) {
  sg::Vec2 s(0.0f);
  parseNumbers("--shutter", text, &s[0], 2, "OPEN,CLOSE (two fractions of the frame interval separated by a comma)");
  return s;
}

std::string aovPath(const std::string& output, const std::string& aov) {
  auto dot = output.find_last_of('.');
  auto slash = output.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return output + "." + aov;
  return output.substr(0, dot) + "." + aov + output.substr(dot);
}

std::string importLimitOption(const sg::ImportLimitError& e) {
  return e.limit() == sg::ImportLimitError::Limit::FileBytes ? "--max-file-mb" : "--max-elements";
}

}  // namespace tsr::app
