#pragma once
// Back-end parameters of a viewport (spp, max depth, seed, ...): named values
// that may change while an image converges, as given; what they mean, their
// types and defaults are the back-end's ParameterTable.
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <variant>

namespace tsr::med {

using ParameterValue = std::variant<bool, std::int64_t, double, std::string>;

class ParameterError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class Parameters {
 public:
  void set(const std::string& name, ParameterValue value) { values_[name] = std::move(value); }
  bool has(const std::string& name) const { return values_.count(name) != 0; }
  const std::map<std::string, ParameterValue>& all() const { return values_; }

  // Typed values with their defaults are read through the back-end's
  // ParameterTable (parameter_table.hpp), which declares them once.

  // Parses "name=value" (true/false, integers, reals, else a string).
  static std::pair<std::string, ParameterValue> parse(const std::string& assignment);

  bool operator==(const Parameters&) const = default;

 private:
  std::map<std::string, ParameterValue> values_;
};

}  // namespace tsr::med
