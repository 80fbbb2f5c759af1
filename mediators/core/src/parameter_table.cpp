#include "tsr/med/parameter_table.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace tsr::med {

namespace {

std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const bool same =
          std::tolower(static_cast<unsigned char>(a[i - 1])) == std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string number(double v) {
  if (std::isinf(v)) return v < 0 ? "-inf" : "inf";
  if (std::abs(v) >= 9e18) return v < 0 ? "min" : "max";  // the ends of std::int64_t
  std::ostringstream s;
  if (v == std::floor(v) && std::abs(v) < 1e15)
    s << static_cast<long long>(v);
  else
    s << v;
  return s.str();
}

const char* typeName(ParameterType t) {
  // In ParameterType's order. The assert catches a table out of step with the
  // enumerators up to the last one named there; a type appended after it
  // needs its name here and the assert moved to it.
  static constexpr std::array kNames{"flag", "integer", "real", "choice"};
  static_assert(kNames.size() == std::size_t(ParameterType::Choice) + 1);
  return std::size_t(t) < kNames.size() ? kNames[std::size_t(t)] : "?";
}

std::string rangeText(const ParameterSpec& s) {
  switch (s.type) {
    case ParameterType::Flag:
      return "true|false";
    case ParameterType::Choice: {
      std::string all;
      for (const auto& c : s.choices) all += (all.empty() ? "" : "|") + (c.empty() ? std::string("\"\"") : c);
      return all;
    }
    default:
      return (s.minExclusive ? "(" : "[") + number(s.min) + ", " + number(s.max) + "]";
  }
}

std::string joined(const std::vector<std::string>& names) {
  std::string all;
  for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
  return all;
}

}  // namespace

std::string describeValue(const ParameterValue& v) {
  return std::visit(
      [](const auto& x) -> std::string {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, bool>)
          return x ? "true" : "false";
        else if constexpr (std::is_same_v<T, std::string>)
          return "'" + x + "'";
        else if constexpr (std::is_same_v<T, double>)
          return number(x);
        else
          return std::to_string(x);
      },
      v);
}

ParameterSpec flagParameter(std::string name, bool fallback, std::string help) {
  return {std::move(name), ParameterType::Flag, fallback, 0, 1, false, {}, std::move(help)};
}
ParameterSpec integerParameter(std::string name, std::int64_t fallback, std::int64_t min, std::int64_t max,
                               std::string help) {
  return {std::move(name), ParameterType::Integer, fallback, double(min), double(max), false, {}, std::move(help)};
}
ParameterSpec realParameter(std::string name, double fallback, double min, double max, std::string help) {
  return {std::move(name), ParameterType::Real, fallback, min, max, false, {}, std::move(help)};
}
ParameterSpec positiveParameter(std::string name, double fallback, double max, std::string help) {
  return {std::move(name), ParameterType::Real, fallback, 0.0, max, true, {}, std::move(help)};
}
ParameterSpec choiceParameter(std::string name, std::string fallback, std::vector<std::string> choices,
                              std::string help) {
  return {std::move(name), ParameterType::Choice, std::move(fallback), 0, 0,
          false,           std::move(choices),    std::move(help)};
}

ParameterTable::ParameterTable(std::string backend, std::vector<ParameterSpec> specs)
    : backend_(std::move(backend)), specs_(std::move(specs)) {
  for (const auto& s : specs_) {
    if (std::count_if(specs_.begin(), specs_.end(), [&](const ParameterSpec& o) { return o.name == s.name; }) > 1)
      throw std::logic_error(backend_ + ": parameter " + s.name + " declared twice");
    validate(s.name, s.fallback);  // a default outside its own range is a declaration bug
  }
}

const ParameterSpec* ParameterTable::find(std::string_view name) const {
  auto it = std::find_if(specs_.begin(), specs_.end(), [&](const ParameterSpec& s) { return s.name == name; });
  return it == specs_.end() ? nullptr : &*it;
}

const ParameterSpec* ParameterTable::nearest(std::string_view name) const {
  const ParameterSpec* best = nullptr;
  std::size_t distance = 3;
  for (const auto& s : specs_)
    if (std::size_t d = editDistance(name, s.name); d < distance) distance = d, best = &s;
  return best;
}

void ParameterTable::validate(const Parameters& p) const {
  for (const auto& [name, value] : p.all()) validate(name, value);
}

void ParameterTable::validate(const std::string& name, const ParameterValue& value) const {
  const ParameterSpec* spec = find(name);
  if (!spec) {
    std::vector<std::string> names;
    for (const auto& s : specs_) names.push_back(s.name);
    const ParameterSpec* typo = nearest(name);
    throw UnknownParameter("unknown parameter '" + name + "' for the " + backend_ + " back-end" +
                           (typo ? " (did you mean " + typo->name + "?)" : "") + "; it takes: " + joined(names));
  }
  auto bad = [&](const std::string& expected) {
    throw BadParameterValue("parameter " + name + " = " + describeValue(value) + ": expected " + expected);
  };
  switch (spec->type) {
    case ParameterType::Flag:
      if (!std::holds_alternative<bool>(value)) bad("true or false");
      return;
    case ParameterType::Choice:
      if (const auto* s = std::get_if<std::string>(&value);
          !s || std::find(spec->choices.begin(), spec->choices.end(), *s) == spec->choices.end())
        bad("one of " + rangeText(*spec));
      return;
    case ParameterType::Integer: {
      const auto* i = std::get_if<std::int64_t>(&value);
      if (!i) bad("an integer in " + rangeText(*spec));
      if (double(*i) < spec->min || double(*i) > spec->max) bad("an integer in " + rangeText(*spec));
      return;
    }
    case ParameterType::Real: {
      double v = 0;
      if (const auto* d = std::get_if<double>(&value))
        v = *d;
      else if (const auto* i = std::get_if<std::int64_t>(&value))
        v = double(*i);
      else
        bad("a number in " + rangeText(*spec));
      if (!std::isfinite(v) || v < spec->min || v > spec->max || (spec->minExclusive && v == spec->min))
        bad("a number in " + rangeText(*spec));
      return;
    }
  }
}

const ParameterSpec& ParameterTable::declared(std::string_view name, ParameterType type) const {
  const ParameterSpec* spec = find(name);
  if (!spec || spec->type != type)
    throw std::logic_error(backend_ + " reads parameter " + std::string(name) + " as a " + typeName(type) +
                           ", which its table does not declare");
  return *spec;
}

const ParameterValue& ParameterTable::valueOf(const Parameters& p, const ParameterSpec& spec) const {
  auto it = p.all().find(spec.name);
  if (it == p.all().end()) return spec.fallback;
  validate(spec.name, it->second);
  return it->second;
}

bool ParameterTable::flag(const Parameters& p, std::string_view name) const {
  return std::get<bool>(valueOf(p, declared(name, ParameterType::Flag)));
}

std::int64_t ParameterTable::integer(const Parameters& p, std::string_view name) const {
  return std::get<std::int64_t>(valueOf(p, declared(name, ParameterType::Integer)));
}

double ParameterTable::real(const Parameters& p, std::string_view name) const {
  const ParameterValue& v = valueOf(p, declared(name, ParameterType::Real));
  if (const auto* i = std::get_if<std::int64_t>(&v)) return double(*i);
  return std::get<double>(v);
}

std::string ParameterTable::choice(const Parameters& p, std::string_view name) const {
  return std::get<std::string>(valueOf(p, declared(name, ParameterType::Choice)));
}

std::string ParameterTable::describe() const {
  std::size_t nameWidth = 4, rangeWidth = 5;
  for (const auto& s : specs_) {
    nameWidth = std::max(nameWidth, s.name.size());
    rangeWidth = std::max(rangeWidth, rangeText(s).size() + std::string(typeName(s.type)).size() + 1);
  }
  std::ostringstream out;
  out << std::left << std::setw(int(nameWidth) + 2) << "name" << std::setw(int(rangeWidth) + 2) << "type"
      << std::setw(12) << "default"
      << "meaning\n";
  for (const auto& s : specs_) {
    std::string fallback = describeValue(s.fallback);
    out << std::setw(int(nameWidth) + 2) << s.name << std::setw(int(rangeWidth) + 2)
        << (std::string(typeName(s.type)) + " " + rangeText(s)) << std::setw(12) << fallback << s.help << "\n";
  }
  return out.str();
}

}  // namespace tsr::med
