#include "input_script.hpp"

#include "sim_math.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <stdexcept>

namespace pushpull::xrsim {
namespace {

[[noreturn]] void fail(const std::string& source, int line, const std::string& what) {
  throw std::runtime_error(source + ":" + std::to_string(line) + ": " + what);
}

XrPosef parse_pose(const nlohmann::json& j, const std::string& source, int line) {
  XrPosef pose = pose_identity();
  if (!j.is_object()) fail(source, line, "\"pose\" must be an object with \"p\" and \"q\"");
  if (j.contains("p")) {
    const auto& p = j["p"];
    if (!p.is_array() || p.size() != 3) fail(source, line, "\"p\" must be [x, y, z]");
    pose.position = {p[0].get<float>(), p[1].get<float>(), p[2].get<float>()};
  }
  if (j.contains("q")) {
    const auto& q = j["q"];
    if (!q.is_array() || q.size() != 4) fail(source, line, "\"q\" must be [x, y, z, w]");
    pose.orientation =
        quat_normalize({q[0].get<float>(), q[1].get<float>(), q[2].get<float>(), q[3].get<float>()});
  }
  return pose;
}

InputValue parse_value(const nlohmann::json& v, const std::string& source, int line) {
  if (v.is_boolean()) return {v.get<bool>() ? 1.f : 0.f, 0.f};
  if (v.is_number()) return {v.get<float>(), 0.f};
  if (v.is_array() && v.size() == 2 && v[0].is_number() && v[1].is_number())
    return {v[0].get<float>(), v[1].get<float>()};
  fail(source, line, "\"value\" must be a boolean, a number or [x, y]");
}

}  // namespace

InputScript InputScript::parse(std::istream& in, const std::string& source) {
  InputScript script;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos || text[first] == '#') continue;
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
      fail(source, line, std::string("not JSON: ") + e.what());
    }
    if (!j.is_object()) fail(source, line, "each line must be a JSON object");
    if (!j.contains("t") || !j["t"].is_number()) {
      if (j.contains("path") || j.contains("event")) fail(source, line, "missing number \"t\" (seconds)");
      continue;  // a header or other record of a recording
    }
    const double t = j["t"].get<double>();
    try {
      if (j.contains("event")) {
        const std::string e = j["event"].get<std::string>();
        ScriptEventKind kind;
        if (e == "exit")
          kind = ScriptEventKind::exit;
        else if (e == "loss")
          kind = ScriptEventKind::loss;
        else if (e == "capture")
          kind = ScriptEventKind::capture;
        else if (e == "recenter")
          kind = ScriptEventKind::recenter;
        else if (e == "failure")
          kind = ScriptEventKind::failure;
        else if (e == "lost")
          kind = ScriptEventKind::lost;
        else
          fail(source, line, "unknown event \"" + e + "\" (exit, loss, lost, capture, recenter, failure)");
        script.events_.push_back({t, kind});
        continue;
      }
      if (!j.contains("path")) continue;  // other records of a recording (push/pull results)
      const std::string path = j["path"].get<std::string>();
      if (path.empty() || path[0] != '/') fail(source, line, "\"path\" must be an OpenXR path");
      if (j.contains("pose")) {
        bool tracked = true;
        if (j.contains("tracked")) {
          if (!j["tracked"].is_boolean()) fail(source, line, "\"tracked\" must be true or false");
          tracked = j["tracked"].get<bool>();
        }
        script.poses_[path].push_back({t, parse_pose(j["pose"], source, line), tracked});
      } else if (j.contains("value")) {
        const InputValue v = parse_value(j["value"], source, line);
        script.values_[path].push_back({t, v});
        if (j["value"].is_array()) {  // a vector2 also sets its components
          script.values_[path + "/x"].push_back({t, {v.x, 0.f}});
          script.values_[path + "/y"].push_back({t, {v.y, 0.f}});
        }
      } else {
        fail(source, line, "a \"path\" line needs \"pose\" or \"value\"");
      }
    } catch (const nlohmann::json::exception& e) {
      fail(source, line, e.what());
    }
  }
  const auto by_time = [](const auto& a, const auto& b) { return a.t < b.t; };
  for (auto& [path, samples] : script.poses_) std::stable_sort(samples.begin(), samples.end(), by_time);
  for (auto& [path, samples] : script.values_) std::stable_sort(samples.begin(), samples.end(), by_time);
  std::stable_sort(script.events_.begin(), script.events_.end(), by_time);
  return script;
}

InputScript InputScript::load(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file + ": cannot open the input script");
  return parse(in, file);
}

std::optional<XrPosef> InputScript::pose_at(const std::string& path, double t) const {
  const auto it = poses_.find(path);
  if (it == poses_.end() || it->second.empty()) return std::nullopt;
  const auto& s = it->second;
  if (t <= s.front().t) return s.front().pose;
  if (t >= s.back().t) return s.back().pose;
  const auto next =
      std::upper_bound(s.begin(), s.end(), t, [](double v, const PoseSample& p) { return v < p.t; });
  const auto prev = next - 1;
  const double span = next->t - prev->t;
  return pose_lerp(prev->pose, next->pose, span > 0 ? (t - prev->t) / span : 1.0);
}

std::optional<bool> InputScript::tracked_at(const std::string& path, double t) const {
  const auto it = poses_.find(path);
  if (it == poses_.end() || it->second.empty()) return std::nullopt;
  const auto& s = it->second;
  const auto next = std::upper_bound(s.begin(), s.end(), t + kTimeTolerance,
                                     [](double v, const PoseSample& p) { return v < p.t; });
  return next == s.begin() ? s.front().tracked : (next - 1)->tracked;
}

std::optional<InputValue> InputScript::value_at(const std::string& path, double t) const {
  t += kTimeTolerance;  // a change at t = n / rate belongs to frame n despite rounding of XrTime
  const auto it = values_.find(path);
  if (it == values_.end()) return std::nullopt;
  const auto& s = it->second;
  const auto next =
      std::upper_bound(s.begin(), s.end(), t, [](double v, const ValueSample& p) { return v < p.t; });
  if (next == s.begin()) return std::nullopt;
  return (next - 1)->value;
}

}  // namespace pushpull::xrsim
