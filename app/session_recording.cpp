#include "session_recording.hpp"

#include "commands.hpp"
#include "review_colour.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "pushpull/deform/method.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>

namespace pushpull::app {
namespace {

// A parser's message as it can be printed: it quotes the bytes it stopped at, which in a binary file are raw
// bytes for the terminal; those outside printable ASCII become \xNN, and at most 200 are kept.
std::string printable(std::string_view text) {
  static const char* const kHex = "0123456789abcdef";
  std::string out;
  for (std::size_t k = 0; k < text.size() && k < 200; ++k) {
    const auto c = static_cast<unsigned char>(text[k]);
    out += c >= 0x20 && c < 0x7f ? std::string(1, static_cast<char>(c))
                                 : std::string("\\x") + kHex[c >> 4] + kHex[c & 15];
  }
  return text.size() > 200 ? out + "..." : out;
}

[[noreturn]] void corrupted(const std::string& path, std::size_t line, const std::string& what) {
  throw CommandError(path + ":" + std::to_string(line) + ": corrupted line: " + what);
}

bool is_method_name(const std::string& name) {
  try {
    (void)deform::parse_method(name);
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

bool finite_vector3(const nlohmann::json& j) {
  if (!j.is_array() || j.size() != 3) return false;
  for (const auto& v : j)
    if (!v.is_number() || !std::isfinite(v.get<double>())) return false;
  return true;
}

// The problem with an input line ("t" lines, read by xr/sim), or "" when it is well formed.
std::string input_line_problem(const nlohmann::json& j) {
  if (!j["t"].is_number()) return "\"t\" is not a number";
  if (j.contains("event")) {
    // The events xr/sim's script knows (an unknown one failed the replay's runtime, blamed on OpenXR).
    if (!j["event"].is_string()) return "\"event\" is not a string";
    const std::string event = j["event"].get<std::string>();
    for (const char* known : {"exit", "loss", "lost", "capture", "recenter", "failure"})
      if (event == known) return "";
    return "unknown event \"" + event + "\" (exit, loss, lost, capture, recenter or failure)";
  }
  if (!j.contains("path") || !j["path"].is_string()) return "an input line needs a string \"path\"";
  if (j.contains("pose")) {
    const auto& pose = j["pose"];
    if (!pose.is_object() || !pose.contains("p") || !pose.contains("q") || !pose["p"].is_array() ||
        pose["p"].size() != 3 || !pose["q"].is_array() || pose["q"].size() != 4)
      return "\"pose\" must be {\"p\": [x, y, z], \"q\": [x, y, z, w]}";
    for (const auto& v : pose["p"])
      if (!v.is_number()) return "\"pose\" has a component that is not a number";
    for (const auto& v : pose["q"])
      if (!v.is_number()) return "\"pose\" has a component that is not a number";
    return "";
  }
  if (j.contains("value")) {
    const auto& v = j["value"];
    if (v.is_number() || v.is_boolean()) return "";
    if (v.is_array() && v.size() == 2 && v[0].is_number() && v[1].is_number()) return "";
    return "\"value\" must be a number, a boolean or [x, y]";
  }
  return "an input line needs \"pose\" or \"value\"";
}

}  // namespace

namespace {

// The recording's lines; `number` is the line being read (for the caller's message on a field of the wrong
// type, which nlohmann's accessors throw from anywhere below).
SessionRecording read_lines(const std::string& path, const std::string& text, std::size_t& number) {
  SessionRecording r;
  r.path = path;
  bool ended = false;
  std::size_t last_input_line = 0;  // the line of the latest input time so far
  std::set<std::uint64_t> committed_requests;  // the requests of the committed releases so far
  // Desktop recordings before format 4 pressed the left menu button for the colour key (a replay's headset
  // loop would open its panel): read as "colour" records instead, cycling from the header's colour map.
  bool legacy_desktop = false;
  ReviewColour legacy_colour = ReviewColour::Displacement;
  std::size_t begin = 0;
  number = 0;
  while (begin < text.size()) {
    ++number;
    const std::size_t newline = text.find('\n', begin);
    const bool complete = newline != std::string::npos;
    const std::string line = text.substr(begin, complete ? newline - begin : std::string::npos);
    begin = complete ? newline + 1 : text.size();
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(line);
    } catch (const nlohmann::json::exception& e) {
      if (!complete) {  // the last line, cut while it was written
        r.cut = "line " + std::to_string(number) + " is cut off (the session stopped while writing it)";
        break;
      }
      corrupted(path, number, "not JSON (" + printable(e.what()) + ")");
    }
    if (!j.is_object()) corrupted(path, number, "not a JSON object");
    if (number > 1 && j.contains("record") && j["record"].is_string() && j["record"] == "header")
      corrupted(path, number, "a second header (two recordings joined?)");
    if (number == 1) {
      if (j.value("record", "") != "header")
        throw CommandError(path + ":1: not a pushpull session recording (the first line is not its header)");
      if (!j.contains("model_sha256") || !j["model_sha256"].is_string() || !j.contains("model") ||
          !j["model"].is_string())
        corrupted(path, 1, "the header lacks \"model\" or \"model_sha256\"");
      if (j.contains("model_relative") && !j["model_relative"].is_string())
        corrupted(path, 1, "the header's \"model_relative\" is not a path");
      // The scale the replay's metrics and lengths are given at (metres per model unit).
      if (j.contains("life_size_scale") &&
          !(j["life_size_scale"].is_number() && std::isfinite(j["life_size_scale"].get<double>()) &&
            j["life_size_scale"].get<double>() > 0.0))
        corrupted(path, 1,
                  "the header's \"life_size_scale\" must be a finite number > 0, got " +
                      j["life_size_scale"].dump());
      // What `pushpull replay` sets the review up from.
      const nlohmann::json* options = j.contains("options") && j["options"].is_object() ? &j["options"] : nullptr;
      if (options == nullptr) corrupted(path, 1, "the header lacks the review's \"options\"");
      for (const char* key : {"method"})
        if (!options->contains(key) || !(*options)[key].is_string())
          corrupted(path, 1, std::string("header option \"") + key + "\" is missing or not a string");
      for (const char* key : {"mu", "handle_radius_m", "roi_radius_m", "distance_m"})
        if (!options->contains(key) || !(*options)[key].is_number())
          corrupted(path, 1, std::string("header option \"") + key + "\" is missing or not a number");
      // The values the replay sets its review up from, checked here so that a damaged header is named as
      // such (not as an option the user never typed, nor as every push/pull failing).
      if (!is_method_name((*options)["method"].get<std::string>()))
        corrupted(path, 1,
                  "header option \"method\" names no deformation method: \"" +
                      (*options)["method"].get<std::string>() + "\"");
      auto positive = [&](const char* key, double above) {
        if (!options->contains(key) || (*options)[key].is_null()) return;  // (null: not given, e.g. length_m)
        const nlohmann::json& v = (*options)[key];
        if (!v.is_number() || !std::isfinite(v.get<double>()) || !(v.get<double>() > above)) {
          std::ostringstream problem;
          problem << "header option \"" << key << "\" must be a finite number > " << above << ", got "
                  << v.dump();
          corrupted(path, 1, problem.str());
        }
      };
      positive("mu", 1.0);
      for (const char* key : {"handle_radius_m", "roi_radius_m", "distance_m", "scale", "length_m"})
        positive(key, 0.0);
      for (const char* key : {"up", "front"}) {
        const bool ok = options->contains(key) && (*options)[key].is_array() && (*options)[key].size() == 3 &&
                        (*options)[key][0].is_number() && (*options)[key][1].is_number() &&
                        (*options)[key][2].is_number();
        if (!ok) corrupted(path, 1, std::string("header option \"") + key + "\" is not [x, y, z]");
        const Eigen::Vector3d axis((*options)[key][0].get<double>(), (*options)[key][1].get<double>(),
                                   (*options)[key][2].get<double>());
        if (!axis.allFinite() || !(axis.stableNorm() > 0.0))
          corrupted(path, 1,
                    std::string("header option \"") + key + "\" must be a finite, non-zero direction");
      }
      {
        // place_on_stage's rule (stage_placement.cpp), so that every review it placed replays.
        auto axis = [&](const char* key) {
          const nlohmann::json& a = (*options)[key];
          const Eigen::Vector3d v(a[0].get<double>(), a[1].get<double>(), a[2].get<double>());
          const double plain = v.norm();
          return plain > 0.0 && std::isfinite(plain) ? v : Eigen::Vector3d(v / v.stableNorm());
        };
        const Eigen::Vector3d up = axis("up").normalized(), front = axis("front");
        if ((front - front.dot(up) * up).norm() < 1e-9 * std::max(1.0, front.norm()))
          corrupted(path, 1, "header options \"up\" and \"front\" are parallel: they place no model");
      }
      if (options->contains("colour") &&
          !((*options)["colour"].is_string() && parse_colour((*options)["colour"].get<std::string>())))
        corrupted(path, 1, "header option \"colour\" names no colour map: " + (*options)["colour"].dump());
      if (j.contains("format") && !j["format"].is_string())
        corrupted(path, 1, "the header's \"format\" is not a string: " + j["format"].dump());
      // The review behaviour a replay of an older recording keeps (a newer one's: the newest this build has).
      if (j.contains("behaviour_format") &&
          !(j["behaviour_format"].is_number_integer() && j["behaviour_format"].get<long long>() >= 1 &&
            j["behaviour_format"].get<long long>() <= 1000000))
        corrupted(path, 1,
                  "the header's \"behaviour_format\" must be a whole number >= 1, got " +
                      j["behaviour_format"].dump());
      r.header = j;
      const std::string format =
          j.contains("format") && j["format"].is_string() ? j["format"].get<std::string>() : std::string();
      const std::string_view prefix = "pushpull-session-";
      if (format.size() > prefix.size() && format.compare(0, prefix.size(), prefix) == 0) {
        int version = 0;
        const char* first = format.data() + prefix.size();
        const char* last = format.data() + format.size();
        const auto [end, error] = std::from_chars(first, last, version);
        if (error == std::errc() && end == last && version > 0) r.format_version = version;
      }
      if (options->contains("desktop") && !(*options)["desktop"].is_boolean())
        corrupted(path, 1, "header option \"desktop\" is not true or false");
      legacy_desktop = options->value("desktop", false) && r.format_version > 0 && r.format_version < 4;
      if (const nlohmann::json* colour = options->contains("colour") ? &(*options)["colour"] : nullptr;
          colour != nullptr && colour->is_string())
        legacy_colour = parse_colour(colour->get<std::string>()).value_or(legacy_colour);
    } else if (j.contains("t")) {
      if (const std::string problem = input_line_problem(j); !problem.empty()) corrupted(path, number, problem);
      // Input lines come in time order (one frame's after another's; a second of slack for a desktop
      // session's rounding): a time over a second before an earlier line's, or past the session's end, is
      // damage (a replay would step its clock towards it without end).
      const double t = j["t"].get<double>();
      if (!(t >= 0.0)) corrupted(path, number, "\"t\" is negative");
      if (t < r.last_input_time - 1.0) {
        std::ostringstream problem;
        problem << "\"t\" " << t << " s is earlier than line " << last_input_line << "'s "
                << r.last_input_time << " s (input lines are in time order: one of the two is damaged)";
        corrupted(path, number, problem.str());
      }
      // The clock counts frames, so consecutive lines are a frame apart: a jump of over a minute is damage
      // too, which a recording cut short (no end record to check against) would otherwise replay for ever.
      // The first line is the first frame's (t = 0): one over a minute later is damage the same way.
      if (last_input_line == 0 && t > 60.0) {
        std::ostringstream problem;
        problem << "\"t\" " << t
                << " s on the first input line (a session's inputs start at its first frame, t = 0)";
        corrupted(path, number, problem.str());
      }
      if (last_input_line > 0 && t > r.last_input_time + 60.0) {
        std::ostringstream problem;
        problem << "\"t\" " << t << " s jumps " << t - r.last_input_time << " s ahead of line "
                << last_input_line << "'s " << r.last_input_time
                << " s (consecutive input lines are a frame apart)";
        corrupted(path, number, problem.str());
      }
      if (t >= r.last_input_time) {
        r.last_input_time = t;
        last_input_line = number;
      }
      if (!r.exit_time && j.value("event", "") == "exit") r.exit_time = t;
      if (legacy_desktop && j.value("path", "") == "/user/hand/left/input/menu/click") {
        if (j.contains("value") && j["value"].is_number() && j["value"].get<double>() > 0.5) {
          legacy_colour = next_colour(legacy_colour);
          r.colour_changes.emplace_back(j["t"].get<double>(), colour_name(legacy_colour));
        }
        r.lines = number;
        continue;  // not in the script
      }
    } else if (j.contains("record")) {
      if (!j["record"].is_string()) corrupted(path, number, "\"record\" is not a string");
      const std::string kind = j["record"];
      // Every record the review writes carries its time in seconds (the replay reads it, e.g. a release's).
      if (j.contains("time") && !(j["time"].is_number() && std::isfinite(j["time"].get<double>())))
        corrupted(path, number, "a record's \"time\" is not a finite number");
      if (kind == "commit") {
        if (!j.contains("hash") || !j["hash"].is_string() || !j.contains("index") ||
            !j["index"].is_number_unsigned())
          corrupted(path, number, "a commit record needs \"index\" and \"hash\"");
        // What a replay with another method compares (d) and reads (the commit's method).
        if (j.contains("d") && !finite_vector3(j["d"]))
          corrupted(path, number, "a commit record's \"d\" must be [x, y, z], finite numbers");
        if (j.contains("method") &&
            !(j["method"].is_string() && is_method_name(j["method"].get<std::string>())))
          corrupted(path, number, "a commit record's \"method\" must be a known method's name");
        // Commits are numbered in order (a line written twice made the replay compare one commit with
        // another's hash).
        if (!r.commits.empty() &&
            !(j["index"].get<std::uint64_t>() > r.commits.back().record["index"].get<std::uint64_t>()))
          corrupted(path, number,
                    "commit index " + j["index"].dump() + " after commit " +
                        r.commits.back().record["index"].dump() + " (line " +
                        std::to_string(r.commits.back().line) + "): a commit repeated or out of order");
        r.commits.push_back({number, j});
      } else if (kind == "release" && j.value("committed", false) && j.contains("request") &&
                 j["request"].is_number_unsigned()) {
        // Each committed release is its own request (a line written twice paired commits with the wrong
        // ones).
        if (!committed_requests.insert(j["request"].get<std::uint64_t>()).second)
          corrupted(path, number,
                    "a committed release of request " + j["request"].dump() + " again (a release repeated)");
      } else if (kind == "method") {
        const bool valid = j.contains("method") && j["method"].is_string() && j.contains("time") &&
                           j["time"].is_number() && is_method_name(j["method"].get<std::string>());
        if (!valid) corrupted(path, number, "a method record needs \"time\" and a known \"method\"");
        r.method_changes.emplace_back(j["time"].get<double>(), j["method"].get<std::string>());
      } else if (kind == "undo" || kind == "redo") {
        if (!j.contains("time") || !j["time"].is_number())
          corrupted(path, number,
                    std::string(kind == "undo" ? "an undo" : "a redo") + " record needs \"time\"");
        r.history_steps.emplace_back(j["time"].get<double>(), kind);
      } else if (kind == "cancel") {
        if (!j.contains("time") || !j["time"].is_number())
          corrupted(path, number, "a cancel record needs \"time\"");
        if (!r.cancels.empty() && j["time"].get<double>() < r.cancels.back())
          corrupted(path, number, "a cancel record earlier than the one before it");
        r.cancels.push_back(j["time"].get<double>());
      } else if (kind == "colour") {
        const bool valid = j.contains("colour") && j["colour"].is_string() && j.contains("time") &&
                           j["time"].is_number() && parse_colour(j["colour"].get<std::string>());
        if (!valid) corrupted(path, number, "a colour record needs \"time\" and a known \"colour\"");
        r.colour_changes.emplace_back(j["time"].get<double>(), j["colour"].get<std::string>());
      } else if (kind == "sizes") {
        const auto positive = [&](const char* key) {
          return j.contains(key) && j[key].is_number() && std::isfinite(j[key].get<double>()) &&
                 j[key].get<double>() > 0.0;
        };
        if (!j.contains("time") || !j["time"].is_number() || !positive("handle_radius") ||
            !positive("roi_radius"))
          corrupted(path, number,
                    "a sizes record needs \"time\" and positive \"handle_radius\" and \"roi_radius\"");
        r.size_changes.push_back(
            {j["time"].get<double>(), j["handle_radius"].get<double>(), j["roi_radius"].get<double>()});
      } else if (kind == "press held") {
        const bool valid = j.contains("time") && j["time"].is_number() && j.contains("from") &&
                           j["from"].is_number() && j.contains("admitted") && j["admitted"].is_boolean() &&
                           j["from"].get<double>() < j["time"].get<double>();
        if (!valid)
          corrupted(path, number, "a press held record needs \"from\" < \"time\" and a boolean \"admitted\"");
        if (!r.press_holds.empty() && j["from"].get<double>() < r.press_holds.back().until)
          corrupted(path, number, "a press held record begins before the previous one ended");
        r.press_holds.push_back({j["from"].get<double>(), j["time"].get<double>(), j["admitted"].get<bool>()});
      } else if (kind == "anchor") {
        const auto finite = [&](const char* key) {
          return j.contains(key) && j[key].is_number() && std::isfinite(j[key].get<double>());
        };
        if (!finite("time") || !finite("x") || !finite("z") || !finite("yaw"))
          corrupted(path, number, "an anchor record needs finite \"time\", \"x\", \"z\" and \"yaw\"");
        if (r.anchor) corrupted(path, number, "a second anchor record (a review anchors the model once)");
        if (j.contains("floor_y") && !finite("floor_y"))
          corrupted(path, number, "an anchor record's \"floor_y\" must be a finite number");
        r.anchor = HeadAnchor{j["time"].get<double>(), j["x"].get<double>(), j["z"].get<double>(),
                              j["yaw"].get<double>(), j.value("floor_y", 0.0)};
      } else if (kind == "clock") {
        // A review records its display rate in whole Hz from 10 to 1000 (review_loop.cpp); a rate outside
        // would stretch the replay's clock without end (1e-9 Hz wrote 2 GB and never finished).
        if (!j.contains("rate_hz") || !j["rate_hz"].is_number() || !(j["rate_hz"].get<double>() >= 10.0) ||
            !(j["rate_hz"].get<double>() <= 1000.0))
          corrupted(path, number,
                    "a clock record's \"rate_hz\" must be a number from 10 to 1000 (frames a second)");
        r.rate_hz = j["rate_hz"].get<double>();
      } else if (kind == "profile" && r.profile.empty()) {
        r.profile = j.value("profile", "");
      } else if (kind == "end") {
        ended = true;
        // The last frame's input is at the end's time (a second of slack, as for the order above).
        if (j.contains("time") && j["time"].is_number() &&
            r.last_input_time > j["time"].get<double>() + 1.0) {
          std::ostringstream problem;
          problem << "\"t\" " << r.last_input_time << " s is after the session's end ("
                  << j["time"].get<double>() << " s, line " << number << ")";
          corrupted(path, last_input_line, problem.str());
        }
      }
      j["line"] = number;
      r.records.push_back(j);
    } else {
      corrupted(path, number, "neither an input line (\"t\") nor a record (\"record\")");
    }
    r.lines = number;
    r.script += line;
    r.script += '\n';
  }
  if (r.header.is_null())
    throw CommandError(path + ":1: the header line is cut off (the session stopped while writing it); nothing "
                       "to replay");
  if (!ended && !r.cut)
    r.cut = "no \"end\" record after line " + std::to_string(r.lines) +
            " (the session crashed or the file was truncated)";
  return r;
}

}  // namespace

SessionRecording read_session_recording(const std::string& path) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (std::filesystem::is_directory(status))
    throw CommandError(path + ": is a folder, not a session recording");
  // Read whole: a device that never ends (/dev/zero) took all memory. (A pipe, replay <(zcat rec.gz), is
  // read.)
  if (!error && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
      !std::filesystem::is_fifo(status))
    throw CommandError(path + ": is a device or a socket, not a session recording");
  if (error && error != std::errc::no_such_file_or_directory)
    throw CommandError(path + ": cannot open the session recording (" + error.message() + ")");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CommandError(path + ": cannot open the session recording");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  if (text.empty()) throw CommandError(path + ": the session recording is empty");
  std::size_t number = 0;
  try {
    return read_lines(path, text, number);
  } catch (const nlohmann::json::exception& e) {  // a field read as the type it should have, and is not
    corrupted(path, number, std::string("a field has the wrong type (") + e.what() + ")");
  }
}

namespace {

bool is_committed_release(const nlohmann::json& r) {
  return r.value("record", "") == "release" && r.value("committed", false) && r.contains("request") &&
         r["request"].is_number_unsigned();
}

}  // namespace

std::vector<std::optional<std::size_t>> release_outcomes(const SessionRecording& recording) {
  std::map<std::uint64_t, std::size_t> commit_of_request;
  for (std::size_t k = 0; k < recording.commits.size(); ++k)
    if (const nlohmann::json& r = recording.commits[k].record;
        r.contains("request") && r["request"].is_number_unsigned())
      commit_of_request.emplace(r["request"].get<std::uint64_t>(), k);
  std::vector<std::optional<std::size_t>> outcomes;
  for (const nlohmann::json& r : recording.records) {
    if (!is_committed_release(r)) continue;
    const auto it = commit_of_request.find(r["request"].get<std::uint64_t>());
    outcomes.push_back(it == commit_of_request.end() ? std::nullopt : std::optional(it->second));
  }
  return outcomes;
}

CommitHistory commit_history(const SessionRecording& recording) {
  const std::vector<std::optional<std::size_t>> outcomes = release_outcomes(recording);
  std::size_t release = 0;
  CommitHistory h;
  std::vector<std::size_t> states{0};  // 0: the model as loaded
  std::size_t position = 0;
  for (const nlohmann::json& r : recording.records) {
    const std::string kind = r.value("record", "");
    if (is_committed_release(r)) {
      const std::optional<std::size_t> commit = outcomes[release++];
      if (!commit) continue;  // failed, or not landed before the end (never entered the history)
      const nlohmann::json& c = recording.commits[*commit].record;
      const std::size_t index = c.contains("index") && c["index"].is_number_unsigned()
                                    ? c["index"].get<std::size_t>()
                                    : *commit + 1;
      states.resize(position + 1);
      states.push_back(index);
      position = states.size() - 1;
      h.steps.push_back("push/pull " + std::to_string(index));
    } else if (kind == "undo") {
      if (position > 0) --position;
      h.steps.push_back("undo");
    } else if (kind == "redo") {
      if (position + 1 < states.size()) ++position;
      h.steps.push_back("redo");
    } else if (kind == "cancel") {  // Esc mid-drag: nothing entered the history
      h.steps.push_back("a drag cancelled");
    }
  }
  h.kept.assign(states.begin() + 1, states.begin() + std::ptrdiff_t(position) + 1);
  return h;
}

}  // namespace pushpull::app
