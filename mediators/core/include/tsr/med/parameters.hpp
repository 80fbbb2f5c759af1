#pragma once
// Back-end parameters of a viewport (spp, max depth, seed, ...): named values
// that may change while an image converges. Reads are typed; a value of the
// wrong type is a ParameterError naming the parameter.
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

  bool getBool(const std::string& name, bool fallback) const;
  std::int64_t getInt(const std::string& name, std::int64_t fallback, std::int64_t min = INT64_MIN,
                      std::int64_t max = INT64_MAX) const;
  double getReal(const std::string& name, double fallback) const;  // accepts integers too
  std::string getString(const std::string& name, const std::string& fallback) const;

  // Parses "name=value" (true/false, integers, reals, else a string).
  static std::pair<std::string, ParameterValue> parse(const std::string& assignment);

  bool operator==(const Parameters&) const = default;

 private:
  std::map<std::string, ParameterValue> values_;
};

}  // namespace tsr::med
