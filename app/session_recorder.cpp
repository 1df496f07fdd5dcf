#include "session_recorder.hpp"

#include "commands.hpp"
#include "review_loop.hpp"
#include "review_setup.hpp"
#include "sha256.hpp"

#include "pushpull/deform/method.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>

namespace pushpull::app {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

json vec3(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

// Floats as the loop read them: a float widened to double prints with enough digits to come back exactly.
json pose_json(const XrPosef& p) {
  return {
      {"p", {double(p.position.x), double(p.position.y), double(p.position.z)}},
      {"q",
       {double(p.orientation.x), double(p.orientation.y), double(p.orientation.z), double(p.orientation.w)}}};
}

// The components a hand's state is written to: those xr::Input binds its actions to in the profile
// (xr::suggested_component), Touch's for a profile it does not know. Empty: none on that hand.
struct ButtonPaths {
  std::array<std::string, 2> trigger, grip, stick, undo, redo, menu;
};

ButtonPaths button_paths(const std::string& profile) {
  const std::string known =
      xr::suggested_component(profile, xr::BoundAction::Trigger, xr::Hand::Right).empty()
          ? std::string("/interaction_profiles/oculus/touch_controller")
          : profile;
  ButtonPaths b;
  for (int h = 0; h < 2; ++h) {
    const auto hand = xr::Hand(h);
    const auto at = [&](xr::BoundAction action) { return xr::suggested_component(known, action, hand); };
    b.trigger[size_t(h)] = at(xr::BoundAction::Trigger);
    b.grip[size_t(h)] = at(xr::BoundAction::Grip);
    b.stick[size_t(h)] = at(xr::BoundAction::Thumbstick);
    b.undo[size_t(h)] = at(xr::BoundAction::Undo);
    b.redo[size_t(h)] = at(xr::BoundAction::Redo);
    b.menu[size_t(h)] = at(xr::BoundAction::Menu);
  }
  return b;
}

constexpr const char* kHands[2] = {"/user/hand/left", "/user/hand/right"};

}  // namespace

std::string hash_text(std::uint64_t hash) {
  char text[32];
  std::snprintf(text, sizeof text, "0x%016llx", static_cast<unsigned long long>(hash));
  return text;
}

std::string default_recording_path() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char name[64];
  std::strftime(name, sizeof name, "review-%Y%m%d-%H%M%S", &utc);
  // Two sessions started within a second (tests, scripts) get their own files.
  fs::path path = fs::path("out") / "recordings" / (std::string(name) + ".jsonl");
  for (int n = 2; fs::exists(path); ++n)
    path = fs::path("out") / "recordings" / (std::string(name) + "-" + std::to_string(n) + ".jsonl");
  return path.string();
}

SessionRecorder::SessionRecorder(const std::string& path, bool required) : path_(path) {
  if (path.empty()) return;
  std::error_code ec;
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty()) fs::create_directories(parent, ec);
  file_.open(path, std::ios::out | std::ios::trunc);
  if (file_) return;
  if (required) throw CommandError(path + ": cannot write the session recording");
  std::fprintf(
      stderr,
      "pushpull review: warning: %s: cannot write the session recording; not recording (--record FILE "
      "names another place)\n",
      path.c_str());
  path_.clear();
}

void SessionRecorder::write_line(const json& line) {
  if (!file_.is_open()) return;
  // (replace: a path that is not UTF-8, from the command line, is written with U+FFFD, not thrown on)
  file_ << line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << '\n' << std::flush;
  if (!file_) throw CommandError(path_ + ": write failed (disk full?) while recording the session");
}

void SessionRecorder::write_header(const ReviewCommandOptions& o, const ReviewSetup& s,
                                   const RecordingContext& c) {
  if (!file_.is_open()) return;
  // JSON holds UTF-8: a model path that is not (a Latin-1 file name) is written with U+FFFD and names no
  // file.
  try {
    (void)json(fs::absolute(o.model).string()).dump();
  } catch (const json::type_error&) {
    std::fprintf(stderr,
                 "pushpull review: warning: %s: the model's path is not UTF-8; the recording names it with "
                 "U+FFFD in its place: replay it with --model FILE\n",
                 path_.c_str());
  }
  std::vector<double> T;
  for (int r = 0; r < 4; ++r)
    for (int col = 0; col < 4; ++col) T.push_back(s.placement.T_stage_model(r, col));
  const deform::DeformOptions& solver = s.interaction.solver;
  json header{{"record", "header"},
              {"format", "pushpull-session-" + std::to_string(kNewestRecordingFormat)},
              // A replay of an older recording behaves as that format's review did (review_loop.hpp), and so
              // does a replay of this replay's recording.
              {"behaviour_format", std::min(o.behaviour_of_format, kNewestRecordingFormat)},
              {"pushpull_version", PUSHPULL_VERSION},
              {"model", fs::absolute(o.model).lexically_normal().string()},
              // Also relative to the recording's folder: a recording kept beside its model (examples/)
              // replays elsewhere.
              {"model_relative", fs::absolute(o.model)
                                     .lexically_normal()
                                     .lexically_relative(fs::absolute(path_).parent_path())
                                     .string()},
              {"model_sha256", sha256_file_hex(o.model)},
              {"life_size_scale", s.life.scale()},
              {"T_stage_model", T},  // row-major 4x4, model (file units) -> stage (metres)
              {"method", std::string(deform::method_name(solver.method))},
              {"mu", solver.mu},
              {"solver",
               {{"asan_base", std::string(deform::method_name(solver.asan_base))},
                {"max_iterations", solver.max_iterations},
                {"tolerance", solver.tolerance},
                {"energy_tolerance", solver.energy_tolerance},
                {"anderson", solver.anderson_window},
                {"sr_arap_alpha", solver.sr_arap_alpha},
                {"arap_h_lambda", solver.arap_h_lambda},
                {"arap_n_rings", solver.arap_n_rings},
                {"smooth_start_min_free", solver.smooth_start_min_free},
                {"coarse_start_min_free", solver.coarse_start_min_free}}},
              {"handle_radius", s.interaction.handle_radius},  // model units
              {"roi_radius", s.interaction.roi_radius},        // model units
              // The command's options, enough to set the same session up again (pushpull replay reads these).
              {"options",
               {{"method", o.method},
                {"mu", o.mu},
                {"handle_radius_m", o.handle_radius_m},
                {"roi_radius_m", o.roi_radius_m},
                {"up", o.up},
                {"front", o.front},
                {"distance_m", o.distance_m},
                {"samples", o.samples},
                {"colour", o.colour},
                {"scale", o.life_size.scale},
                {"length_m", o.life_size.length_m ? json(*o.life_size.length_m) : json(nullptr)},
                {"desktop", o.desktop}}},
              {"runtime", c.runtime},
              {"view_configuration", c.view_configuration},
              {"eye_size", {c.eye_width, c.eye_height}},
              {"rate_hz", c.rate_hz}};
  write_line(header);
}

void SessionRecorder::write_value(double t, const std::string& path, const json& value) {
  auto it = last_value_.find(path);
  if (it != last_value_.end() && it->second == value) return;
  last_value_[path] = value;
  write_line({{"t", t}, {"path", path}, {"value", value}});
}

void SessionRecorder::write_frame_input(double t, const std::optional<XrPosef>& head,
                                        const std::array<xr::HandInput, 2>& hands,
                                        const std::string& profile) {
  if (!file_.is_open()) return;
  if (profile != profile_ && !profile.empty()) {
    profile_ = profile;
    write_record("profile", t, {{"profile", profile}});
  }
  if (head) write_line({{"t", t}, {"path", "/user/head"}, {"pose", pose_json(*head)}});
  const ButtonPaths b = button_paths(profile_);
  for (size_t h = 0; h < 2; ++h) {
    const xr::HandInput& in = hands[h];
    const std::string hand = kHands[h];
    if (in.T_stage_aim) {
      json line{{"t", t}, {"path", hand + "/input/aim/pose"}, {"pose", pose_json(*in.T_stage_aim)}};
      if (!in.aim_position_tracked) line["tracked"] = false;  // a guess: the replay's runtime reports it so
      write_line(line);
    }
    if (!b.trigger[h].empty()) write_value(t, hand + b.trigger[h], double(in.trigger));
    if (!b.grip[h].empty()) write_value(t, hand + b.grip[h], double(in.grip));
    if (!b.stick[h].empty())
      write_value(t, hand + b.stick[h], json{double(in.thumbstick.x), double(in.thumbstick.y)});
    // Buttons: a press (went down since the last frame) is 1 at this frame and 0 at the next.
    const std::array<std::pair<const std::string*, bool>, 3> buttons{
        {{&b.undo[h], in.undo_pressed}, {&b.redo[h], in.redo_pressed}, {&b.menu[h], in.menu_pressed}}};
    for (const auto& [component, pressed] : buttons) {
      if (component->empty()) continue;
      const std::string path = hand + *component;
      if (pressed) {
        write_value(t, path, 1.0);
        button_down_[path] = true;
      } else if (button_down_[path]) {
        write_value(t, path, 0.0);
        button_down_[path] = false;
      }
    }
  }
}

void SessionRecorder::write_sizes(double t, double handle_radius, double roi_radius) {
  write_record("sizes", t, {{"handle_radius", handle_radius}, {"roi_radius", roi_radius}});
}

void SessionRecorder::write_colour(double t, ReviewColour colour) {
  write_record("colour", t, {{"colour", colour_name(colour)}});
}

void SessionRecorder::write_method(double t, deform::Method method) {
  write_record("method", t, {{"method", std::string(deform::method_name(method))}});
}

void SessionRecorder::write_event_input(double t, const std::string& event) {
  write_line({{"t", t}, {"event", event}});
}

void SessionRecorder::write_interaction(double t, const InteractionEvent& e, double handle_radius,
                                        double roi_radius) {
  const char* hand = e.hand == 0 ? "left" : "right";
  if (e.kind == InteractionEvent::Kind::Pressed) {
    write_record("press", t,
                 {{"hand", hand},
                  {"face", e.face},
                  {"p0", vec3(e.p0)},
                  {"handle", {{"face", e.face}, {"radius", handle_radius}}},
                  {"roi_radius", roi_radius}});
    last_drag_d_.setConstant(std::numeric_limits<double>::quiet_NaN());
    return;
  }
  write_record("release", t,
               {{"hand", hand},
                {"face", e.face},
                {"p0", vec3(e.p0)},
                {"p1", vec3(e.p0 + e.d)},
                {"d", vec3(e.d)},
                {"committed", e.kind == InteractionEvent::Kind::Committed},
                {"request", e.request}});
}

void SessionRecorder::write_drag(double t, const Eigen::Vector3d& d) {
  if (d == last_drag_d_) return;
  last_drag_d_ = d;
  write_record("drag", t, {{"d", vec3(d)}});
}

void SessionRecorder::write_commit(double t, const CommitRecord& c) {
  const deform::Snapshot& s = *c.snapshot;
  write_record("commit", t,
               {{"index", c.index},
                {"hash", hash_text(c.hash)},
                {"request", s.request},
                {"method", std::string(deform::method_name(s.method))},
                {"d", vec3(s.d)},
                {"iterations", s.iteration},
                {"converged", s.converged},
                {"error_estimate", s.error_estimate ? json(*s.error_estimate) : json(nullptr)},
                {"max_displacement", s.max_displacement},
                // The handle and region the worker grew from p0 (vertex counts; the vertices are in the
                // replay's metrics).
                {"handle_vertices", s.region ? s.region->handle.size() : 0},
                {"region_vertices", s.region ? s.region->size() : 0}});
}

void SessionRecorder::write_record(const std::string& kind, double t, json fields) {
  fields["record"] = kind;
  fields["time"] = t;
  write_line(fields);
}

std::string kept_work_note(const std::string& out, const SessionRecorder& recorder) {
  if (!out.empty()) return " (the committed model was written to " + out + ")";
  if (recorder.recording())
    return " (`pushpull replay " + recorder.path() + " --out FOLDER` rebuilds the committed model)";
  return "";
}

}  // namespace pushpull::app
