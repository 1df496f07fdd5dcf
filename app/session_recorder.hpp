// The review's session recording (`pushpull review --record FILE`): JSON Lines, written as the session goes
// and flushed after every line, so a crash keeps everything up to the crash.
//
//   {"record":"header","format":"pushpull-session-6","model":..,"model_sha256":..,"T_stage_model":[16],..}
//   {"t":0.0,"path":"/user/head","pose":{"p":[x,y,z],"q":[x,y,z,w]}}              input, xr/sim script format
//   {"t":0.0,"path":"/user/hand/right/input/trigger/value","value":0.0}
//   {"record":"press","time":0.5,"hand":"right","face":12,"p0":[..],"handle_radius":..,"roi_radius":..}
//   {"record":"drag","time":0.53,"d":[..]}     {"record":"release","time":1.0,"p1":[..],"d":[..]}
//   {"record":"commit","time":1.1,"index":1,"hash":"0x..","iterations":..,"converged":..}
//   {"record":"undo","time":..} {"record":"redo","time":..} {"record":"profile","time":..,"profile":".."}
//   {"record":"press held","time":1.2,"from":1.13,"admitted":true}   a press held back while solving
//                                                                     (press_hold.hpp), ended at "time"
//   {"record":"anchor","time":0.0,"x":..,"z":..,"yaw":..}   the model moved in front of the reviewer's head
//                                                            (head_anchor.hpp; T_stage_model is before it)
//   {"record":"colour","time":..,"colour":"curvature-sign"}   the colour map shown from this frame on
//   {"record":"sizes","time":..,"handle_radius":..,"roi_radius":..}   sizes set by a key (desktop)
//   {"record":"cancel","time":..}   the reviewer cancelled the drag in progress (desktop: Esc mid-drag)
// Format 2 adds "press held" (headset recordings; the desktop shows a hold as its trigger staying released),
// format 3 "anchor" (headset recordings), format 4 "colour" (every colour-map change; desktop recordings no
// longer press the left menu button for the colour key), format 5 "sizes" (the desktop's size keys), format 6
// no record but two-grip scaling on the floor; `pushpull replay` reads 1 to 6 alike (a recording without
// holds is replayed as format 1 was, one without an anchor keeps the header's placement, a desktop one before
// format 4 has its menu presses read as colour changes, one before format 6 scales about the hands).
//   {"record":"end","time":..,"commits":n,"hash":".."}
//
// Input lines carry "t" and an OpenXR path. t counts the loop's frames: frame n at n / rate (the "clock"
// record gives the rate, whole Hz), exactly where xr/sim's virtual clock puts its frame n, so a replay reads
// at every frame what the loop read at the same frame, whatever the headset's timing was; derived records
// carry "record" and "time" but no "t", so xr/sim skips them and the recording is its input script unchanged.
// Poses: stage space, metres, the float values the loop read (written exactly); aim poses and the head are
// written every frame (the runtime interpolates between lines, so holding and moving are both reproduced at
// the recorded frame times); values only when they change; a button that went down is written as 1 at that
// frame and 0 at the next. Derived positions (p0, p1, d) are model space, file units. Hashes are
// deform::position_hash of the committed positions, as "0x" and 16 hex digits.
//
// Ownership: owns the file. Thread-safety: one thread (the frame loop).
#pragma once

#include "commit_watch.hpp"
#include "review_colour.hpp"
#include "review_interaction.hpp"

#include "pushpull/xr/input.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <string>

namespace pushpull::app {

// The format this version writes ("pushpull-session-9") and the newest `pushpull replay` knows. Format 6:
// two-grip scaling keeps the model on its floor (grab_placement.hpp), and a trigger the grip or the menu
// panel gives back still pulled must be let go before it presses; a replay of format 1-5 scales about the
// hands' midpoint and lets such a trigger press at once, as those reviews did. Format 7: the right trackpad
// (htc/vive) steps the sizes by clicks on its rim instead of steering them while touched
// (size_steering.hpp); a replay of format 1-6 steers them as those reviews did. Format 8: a grip squeezed
// during a drag, or held through a lost session, must be let go before it grabs the model (it grabbed at
// the trigger's release); a replay of format 1-7 lets it grab at once. Format 9 adds "cancel" (Esc mid-drag
// in the desktop window cancels the drag; a replay cancels it at that frame). The header's "behaviour_format"
// says which behaviour the recorded review had (a replay of an older recording writes the older number), and
// a replay follows it.
inline constexpr int kNewestRecordingFormat = 9;

struct ReviewCommandOptions;
struct ReviewSetup;

// Where the runtime side of the session came from (header fields).
struct RecordingContext {
  std::string runtime;             // OpenXR runtime name, or "desktop"
  std::string view_configuration;  // "stereo" (headset) or "desktop window"
  int eye_width = 0, eye_height = 0;
  double rate_hz = 0.0;  // display refresh rate (1 / predicted display period); 0 when unknown
};

// "0x" and 16 lowercase hex digits.
[[nodiscard]] std::string hash_text(std::uint64_t hash);

// The default recording path: out/recordings/review-YYYYMMDD-HHMMSS.jsonl under the current folder (UTC),
// with -2, -3, ... when that file exists.
[[nodiscard]] std::string default_recording_path();

class SessionRecorder;
// For the message of a review that ended on an error: where its committed work is (" (the committed model was
// written to OUT)" with --out, else how the recording rebuilds it, else "").
[[nodiscard]] std::string kept_work_note(const std::string& out, const SessionRecorder& recorder);

class SessionRecorder {
 public:
  // Creates the file (and its folder); an empty path records nothing. When the file cannot be created: throws
  // CommandError naming it if `required` (the user named it), else warns on stderr and records nothing (the
  // default path in a folder that cannot be written must not stop a review).
  explicit SessionRecorder(const std::string& path, bool required = true);
  [[nodiscard]] bool recording() const { return file_.is_open(); }
  [[nodiscard]] const std::string& path() const { return path_; }

  // The header: model file and SHA-256, life-size scale, T_stage_model (row-major 4x4, model -> stage),
  // method, mu and every solver option, radii, placement options, pushpull version, runtime.
  void write_header(const ReviewCommandOptions& options, const ReviewSetup& setup,
                    const RecordingContext& context);
  // One headset frame as the loop read it: t (frame clock, above), head pose (stage), both hands.
  // `profile` is the interaction profile the runtime chose (names the button paths; a change is recorded).
  void write_frame_input(double t, const std::optional<XrPosef>& head,
                         const std::array<xr::HandInput, 2>& hands, const std::string& profile);
  // The method of the next push/pulls changed (a key in the window): a derived record that `pushpull replay`
  // applies at the same frame.
  void write_method(double t, deform::Method method);
  // {"record":"colour","time":t,"colour":"curvature-sign"}: the colour map shown from this frame on.
  void write_colour(double t, ReviewColour colour);
  // {"record":"sizes","time":t,"handle_radius":..,"roi_radius":..} (model units): the sizes a key set, from
  // this frame's press on (the headset's thumbstick is replayed from its input instead).
  void write_sizes(double t, double handle_radius, double roi_radius);
  // A runtime event at t as an xr/sim script line ({"t":..,"event":"loss"}): what the loop saw happen.
  void write_event_input(double t, const std::string& event);
  // press / release (commit or cancel) from the interaction; release carries p1 = p0 + d and d.
  void write_interaction(double t, const InteractionEvent& event, double handle_radius, double roi_radius);
  // A drag update: the d the interaction submitted (written when it changed).
  void write_drag(double t, const Eigen::Vector3d& d);
  // A commit the service finished: its index, hash and how the solve went.
  void write_commit(double t, const CommitRecord& commit);
  // Any other derived record ("undo", "redo", "end", ...): `fields` gets "record" and "time".
  void write_record(const std::string& kind, double t, nlohmann::json fields = nlohmann::json::object());

 private:
  void write_line(const nlohmann::json& line);
  void write_value(double t, const std::string& path, const nlohmann::json& value);

  std::string path_;
  std::ofstream file_;
  std::string profile_;
  std::map<std::string, nlohmann::json> last_value_;  // path -> last written value
  std::map<std::string, bool> button_down_;           // path -> written as 1 at the previous frame
  Eigen::Vector3d last_drag_d_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
};

}  // namespace pushpull::app
