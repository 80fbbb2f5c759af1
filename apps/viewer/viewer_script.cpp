#include "viewer_script.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include "text_file.hpp"

namespace tsr::app {

namespace {

constexpr std::size_t kMaxScriptBytes = std::size_t{1} << 20;
constexpr std::size_t kMaxActions = 100000;

std::vector<std::string> splitWords(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

class LineParser {
 public:
  LineParser(std::string where, const ScriptLimits& limits) : where_(std::move(where)), limits_(limits) {}

  [[noreturn]] void fail(const std::string& what) const { throw ScriptError(where_ + ": " + what); }

  double real(const std::string& text, const char* what, double lo, double hi) const {
    double v = 0;
    auto [end, err] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (err != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
      fail(std::string(what) + " '" + text + "' is not a number");
    if (v < lo || v > hi) fail(std::string(what) + " " + text + " is outside " + fmt(lo) + " .. " + fmt(hi));
    return v;
  }
  std::int64_t integer(const std::string& text, const char* what, std::int64_t lo, std::int64_t hi) const {
    std::int64_t v = 0;
    auto [end, err] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (err != std::errc() || end != text.data() + text.size())
      fail(std::string(what) + " '" + text + "' is not an integer");
    if (v < lo || v > hi)
      fail(std::string(what) + " " + text + " is outside " + std::to_string(lo) + " .. " + std::to_string(hi));
    return v;
  }
  std::uint32_t viewport(const std::string& text) const {
    return static_cast<std::uint32_t>(integer(text, "viewport", 0, std::int64_t(limits_.viewports) - 1));
  }
  void arity(const std::vector<std::string>& words, std::size_t lo, std::size_t hi, const char* usage) const {
    if (words.size() < lo || words.size() > hi) fail(std::string("usage: ") + usage);
  }

 private:
  static std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }
  std::string where_;
  const ScriptLimits& limits_;
};

ScriptAction parseLine(const std::vector<std::string>& w, const std::string& where, const ScriptLimits& limits) {
  LineParser p(where, limits);
  ScriptAction a;
  a.where = where;
  a.verb = w[0];
  a.words.assign(w.begin() + 1, w.end());
  const std::string& verb = w[0];
  if (verb == "backend") {
    p.arity(w, 3, 3, "backend VIEWPORT NAME");
    a.viewport = p.viewport(w[1]);
    const auto& known = limits.backends;
    if (std::find(known.begin(), known.end(), w[2]) == known.end()) {
      std::string list;
      for (const auto& b : known) list += (list.empty() ? "" : ", ") + b;
      p.fail("unknown back-end '" + w[2] + "' (this build has " + list + ")");
    }
  } else if (verb == "orbit" || verb == "tilt") {
    p.arity(w, 2, 2, (verb + " DEGREES").c_str());
    a.number = p.real(w[1], "degrees", -3600, 3600);
  } else if (verb == "pan") {
    p.arity(w, 3, 3, "pan DX DY");
    a.number = p.real(w[1], "DX", -100, 100);
    a.number2 = p.real(w[2], "DY", -100, 100);
  } else if (verb == "zoom") {
    p.arity(w, 2, 2, "zoom FACTOR");
    a.number = p.real(w[1], "factor", 1e-3, 1e3);
  } else if (verb == "wait") {
    p.arity(w, 3, 3, "wait frames N | wait samples N");
    if (w[1] == "frames") {
      a.verb = "wait-frames";
      a.count = p.integer(w[2], "frames", 0, 1000000);
    } else if (w[1] == "samples") {
      a.verb = "wait-samples";
      a.count = p.integer(w[2], "samples", 1, 1 << 20);
    } else {
      p.fail("wait what? 'wait frames N' or 'wait samples N'");
    }
  } else if (verb == "param") {
    p.arity(w, 3, 3, "param VIEWPORT NAME=VALUE");
    a.viewport = p.viewport(w[1]);
    const auto eq = w[2].find('=');
    if (eq == std::string::npos || eq == 0) p.fail("expected NAME=VALUE, got '" + w[2] + "'");
  } else if (verb == "limit") {
    p.arity(w, 2, 2, "limit N");
    a.count = p.integer(w[1], "sample limit", 1, 1 << 20);
  } else if (verb == "pause" || verb == "resume") {
    p.arity(w, 1, 1, verb.c_str());
  } else if (verb == "raster-while-moving") {
    p.arity(w, 2, 2, "raster-while-moving on|off");
    if (w[1] != "on" && w[1] != "off") p.fail("expected on or off, got '" + w[1] + "'");
    a.count = w[1] == "on";
  } else if (verb == "workload") {
    p.arity(w, 2, 2, "workload on|off");
    if (w[1] != "on" && w[1] != "off") p.fail("expected on or off, got '" + w[1] + "'");
    a.count = w[1] == "on";
  } else if (verb == "time") {
    p.arity(w, 2, 2, "time SECONDS");
    a.number = p.real(w[1], "time", 0, 1e6);
  } else if (verb == "lens") {
    p.arity(w, 3, 3, "lens APERTURE FOCUS-DISTANCE");
    a.number = p.real(w[1], "aperture", 0, 1e12);
    a.number2 = p.real(w[2], "focus distance", 1e-6, 1e12);
  } else if (verb == "shutter") {
    p.arity(w, 3, 3, "shutter OPEN CLOSE");
    a.number = p.real(w[1], "shutter open", 0, 1);
    a.number2 = p.real(w[2], "shutter close", a.number, 1);
  } else if (verb == "focus-on") {
    p.arity(w, 4, 4, "focus-on VIEWPORT X Y");
    a.viewport = p.viewport(w[1]);
    a.count = p.integer(w[2], "X", 0, 32767);
    a.number2 = double(p.integer(w[3], "Y", 0, 32767));
  } else if (verb == "pick") {
    p.arity(w, 4, 4, "pick VIEWPORT X Y");
    a.viewport = p.viewport(w[1]);
    a.count = p.integer(w[2], "X", 0, 32767);
    a.number2 = double(p.integer(w[3], "Y", 0, 32767));
  } else if (verb == "bookmark") {
    p.arity(w, 3, 3, "bookmark save NAME | bookmark load NAME");
    if (w[1] != "save" && w[1] != "load") p.fail("bookmark save NAME or bookmark load NAME");
  } else if (verb == "screenshot") {
    p.arity(w, 2, 3, "screenshot FILE [VIEWPORT]");
    if (w.size() == 3) a.viewport = p.viewport(w[2]);
  } else if (verb == "window-screenshot") {
    p.arity(w, 2, 2, "window-screenshot FILE");
  } else if (verb == "open") {
    p.arity(w, 2, 2, "open SCENE");
  } else if (verb == "report") {
    p.arity(w, 1, 1, "report");
  } else {
    p.fail("unknown action '" + verb +
           "' (backend, orbit, tilt, pan, zoom, wait, param, limit, pause, resume, raster-while-moving, workload, "
           "time, lens, shutter, focus-on, pick, bookmark, screenshot, window-screenshot, open, report)");
  }
  return a;
}

}  // namespace

std::vector<ScriptAction> parseScriptText(const std::string& text, const std::string& name,
                                          const ScriptLimits& limits) {
  if (text.size() > kMaxScriptBytes) throw ScriptError(name + ": larger than 1 MiB");
  std::vector<ScriptAction> actions;
  std::istringstream in(text);
  std::size_t number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    const std::string where = name + ":" + std::to_string(number);
    if (line.find('\0') != std::string::npos) throw ScriptError(where + ": a NUL byte (not a text file?)");
    const auto words = splitWords(line);
    if (words.empty() || words[0][0] == '#') continue;
    if (actions.size() == kMaxActions) throw ScriptError(where + ": more than 100000 actions");
    actions.push_back(parseLine(words, where, limits));
  }
  return actions;
}

std::vector<ScriptAction> parseScript(const std::string& path, const ScriptLimits& limits) {
  return parseScriptText(readTextFile<ScriptError>(path, kMaxScriptBytes), path, limits);
}

}  // namespace tsr::app
