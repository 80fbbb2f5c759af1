#pragma once
// The shared vocabulary says what is wrong with a value (invalidReason);
// each back-end throws that as its own Error, so the back-end's callers
// still catch one type for every invalid argument.
namespace tsr::backend {

// Throws Error(reason) when value.invalidReason() names one.
template <class Error, class Value>
void validate(const Value& value) {
  if (auto why = value.invalidReason()) throw Error(*why);
}

}  // namespace tsr::backend
