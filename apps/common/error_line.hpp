#pragma once
// The one line a program prints when it stops on an error: "error: " and
// the message with its line breaks flattened, so that a person (and a
// script) reads one line per failure.
#include <iostream>
#include <string>

namespace tsr::app {

inline std::string oneLine(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

inline void printError(const std::string& message) { std::cerr << "error: " << oneLine(message) << "\n"; }

}  // namespace tsr::app
