#include "tsr/med/parameters.hpp"

#include <charconv>
#include <cmath>

namespace tsr::med {

std::pair<std::string, ParameterValue> Parameters::parse(const std::string& assignment) {
  auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) throw ParameterError("parameter '" + assignment + "': expected name=value");
  std::string name = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  if (text == "true") return {name, true};
  if (text == "false") return {name, false};
  std::int64_t i;
  auto [iend, ierr] = std::from_chars(text.data(), text.data() + text.size(), i);
  if (ierr == std::errc() && iend == text.data() + text.size() && !text.empty()) return {name, i};
  double d;
  auto [dend, derr] = std::from_chars(text.data(), text.data() + text.size(), d);
  if (derr == std::errc() && dend == text.data() + text.size() && !text.empty() && std::isfinite(d)) return {name, d};
  return {name, text};
}

}  // namespace tsr::med
