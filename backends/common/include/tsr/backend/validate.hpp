#pragma once
// The shared vocabulary says what is wrong with a value (invalidReason);
// each back-end throws that as its own Error, so the back-end's callers
// still catch one type for every invalid argument.
namespace tsr::backend {

// Throws Error(reason) when value.invalidReason(context...) names one.
template <class Error, class Value, class... Context>
void validate(const Value& value, const Context&... context) {
  if (auto why = value.invalidReason(context...)) throw Error(*why);
}

}  // namespace tsr::backend
