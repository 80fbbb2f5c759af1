#include "tsr/med/parameters.hpp"

#include <charconv>
#include <cmath>

namespace tsr::med {

namespace {
std::string describe(const ParameterValue& v) {
  return std::visit(
      [](const auto& x) -> std::string {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, bool>)
          return x ? "true" : "false";
        else if constexpr (std::is_same_v<T, std::string>)
          return "'" + x + "'";
        else
          return std::to_string(x);
      },
      v);
}
[[noreturn]] void wrongType(const std::string& name, const char* expected, const ParameterValue& v) {
  throw ParameterError("parameter " + name + ": expected " + expected + ", got " + describe(v));
}
}  // namespace

bool Parameters::getBool(const std::string& name, bool fallback) const {
  auto it = values_.find(name);
  if (it == values_.end()) return fallback;
  if (const bool* b = std::get_if<bool>(&it->second)) return *b;
  wrongType(name, "true or false", it->second);
}

std::int64_t Parameters::getInt(const std::string& name, std::int64_t fallback, std::int64_t min,
                                std::int64_t max) const {
  auto it = values_.find(name);
  if (it == values_.end()) return fallback;
  const std::int64_t* i = std::get_if<std::int64_t>(&it->second);
  if (!i) wrongType(name, "an integer", it->second);
  if (*i < min || *i > max)
    throw ParameterError("parameter " + name + ": " + std::to_string(*i) + " is outside [" + std::to_string(min) +
                         ", " + std::to_string(max) + "]");
  return *i;
}

double Parameters::getReal(const std::string& name, double fallback) const {
  auto it = values_.find(name);
  if (it == values_.end()) return fallback;
  if (const double* d = std::get_if<double>(&it->second)) return *d;
  if (const std::int64_t* i = std::get_if<std::int64_t>(&it->second)) return static_cast<double>(*i);
  wrongType(name, "a number", it->second);
}

std::string Parameters::getString(const std::string& name, const std::string& fallback) const {
  auto it = values_.find(name);
  if (it == values_.end()) return fallback;
  if (const std::string* s = std::get_if<std::string>(&it->second)) return *s;
  wrongType(name, "a string", it->second);
}

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
