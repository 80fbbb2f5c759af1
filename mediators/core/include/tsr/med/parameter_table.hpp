#pragma once
// The parameters a back-end understands, declared once: name, type,
// default, range and one line of help. Viewports read typed values through
// the table (never a default written at the call), and everything that
// takes parameters from outside — a command line, a viewer script, a
// message from the client — is checked against it: an unknown name or a
// bad value is a typed error that names what would be valid.
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "tsr/med/parameters.hpp"

namespace tsr::med {

// A name the back-end does not declare.
class UnknownParameter : public ParameterError {
 public:
  using ParameterError::ParameterError;
};
// A declared name with a value of the wrong type or outside its range.
class BadParameterValue : public ParameterError {
 public:
  using ParameterError::ParameterError;
};

enum class ParameterType : std::uint8_t { Flag, Integer, Real, Choice };

struct ParameterSpec {
  std::string name;
  ParameterType type = ParameterType::Integer;
  ParameterValue fallback;  // the default: bool, int64, double or string as the type says
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool minExclusive = false;         // a real that must be above min
  std::vector<std::string> choices;  // Choice: the values allowed
  std::string help;
};

// Shorthands for declaring a table.
ParameterSpec flagParameter(std::string name, bool fallback, std::string help);
ParameterSpec integerParameter(std::string name, std::int64_t fallback, std::int64_t min, std::int64_t max,
                               std::string help);
ParameterSpec realParameter(std::string name, double fallback, double min, double max, std::string help);
ParameterSpec positiveParameter(std::string name, double fallback, double max, std::string help);  // (0, max]
ParameterSpec choiceParameter(std::string name, std::string fallback, std::vector<std::string> choices,
                              std::string help);

class ParameterTable {
 public:
  ParameterTable() = default;
  ParameterTable(std::string backend, std::vector<ParameterSpec> specs);

  const std::string& backend() const { return backend_; }
  const std::vector<ParameterSpec>& specs() const { return specs_; }
  const ParameterSpec* find(std::string_view name) const;
  bool declares(std::string_view name) const { return find(name) != nullptr; }
  // The declared name closest to `name`, within two edits (a typo), or null.
  const ParameterSpec* nearest(std::string_view name) const;

  // Throws UnknownParameter or BadParameterValue for the first offender.
  void validate(const Parameters& p) const;
  void validate(const std::string& name, const ParameterValue& value) const;

  // The value of a declared parameter: the one given, checked, or the
  // default. Asking for an undeclared name is a programming error
  // (std::logic_error).
  bool flag(const Parameters& p, std::string_view name) const;
  std::int64_t integer(const Parameters& p, std::string_view name) const;
  double real(const Parameters& p, std::string_view name) const;  // integers are accepted
  std::string choice(const Parameters& p, std::string_view name) const;

  // One line per parameter: name, type and range, default, help.
  std::string describe() const;

 private:
  const ParameterSpec& declared(std::string_view name, ParameterType type) const;
  const ParameterValue& valueOf(const Parameters& p, const ParameterSpec& spec) const;

  std::string backend_;
  std::vector<ParameterSpec> specs_;
};

// A value as a person writes it: true, 16, 0.5, 'pixel'.
std::string describeValue(const ParameterValue& v);

}  // namespace tsr::med
