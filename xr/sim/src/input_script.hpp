// The simulated runtime's input script: JSON Lines, one input change per line, keyed by OpenXR paths.
//
//   {"t": 1.0, "path": "/user/hand/right/input/aim/pose", "pose": {"p": [0.1, 1.2, -0.5], "q": [0, 0, 0, 1]}}
//   {"t": 2.0, "path": "/user/hand/left/input/menu/click", "value": true}
//   {"t": 2.5, "path": "/user/hand/left/input/thumbstick", "value": [0.0, 1.0]}
//   {"t": 0.0, "path": "/user/head", "pose": {...}}
//   {"t": 9.0, "event": "exit"}      also "loss", "capture", "recenter", "failure" (the next
//                                    xrBeginFrame fails with XR_ERROR_RUNTIME_FAILURE, as runtimes sometimes
//                                    do) and "lost" (the next xrEndFrame fails with XR_ERROR_SESSION_LOST,
//                                    the session lost in the middle of the app's frame, then as "loss")
//
// Times are seconds from the start of the session's frame clock. Poses are T_stage_device (STAGE
// space, meters, unit quaternions x y z w) and are interpolated between samples (slerp), held before
// the first and after the last sample: a pose moves toward its path's next sample from the moment of the one
// before, so holding still until a later move takes a second sample with the same pose just before it. Values (bool as 0/1, float, vector2 [x, y]) hold until changed.
// Lines that are empty or start with '#' are skipped; other lines may carry extra keys (recordings do).
// An InputScript is immutable after parsing; const member functions are thread-safe.
#pragma once

#include <openxr/openxr.h>

#include <istream>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace pushpull::xrsim {

// A scalar or two-component input value: bool (0 or 1), float (x), vector2 (x, y).
struct InputValue {
  float x = 0.f;
  float y = 0.f;
  bool operator==(const InputValue&) const = default;
};

enum class ScriptEventKind { exit, loss, capture, recenter, failure, lost };

struct ScriptEvent {
  double t = 0.0;  // seconds
  ScriptEventKind kind = ScriptEventKind::exit;
};

class InputScript {
 public:
  // Samples and events within this many seconds after a query time count as reached.
  static constexpr double kTimeTolerance = 1e-6;

  // Parses a script; throws std::runtime_error naming `source_name`, the line and the problem.
  static InputScript parse(std::istream& in, const std::string& source_name);
  static InputScript load(const std::string& file);

  // The pose of `path` at time t (seconds), interpolated; nullopt when the script never sets it.
  std::optional<XrPosef> pose_at(const std::string& path, double t) const;
  // Whether the pose of `path` at t is tracked: the "tracked" flag of the latest sample at or before t (a
  // line's "tracked": false = the runtime's guess of a device out of its cameras' view: located, not
  // tracked); nullopt when the script never sets the pose.
  std::optional<bool> tracked_at(const std::string& path, double t) const;
  // The latest value of `path` set at or before t; nullopt when none was set yet.
  std::optional<InputValue> value_at(const std::string& path, double t) const;
  // Events sorted by time.
  const std::vector<ScriptEvent>& events() const { return events_; }
  bool empty() const { return poses_.empty() && values_.empty() && events_.empty(); }

 private:
  struct PoseSample {
    double t;
    XrPosef pose;
    bool tracked = true;
  };
  struct ValueSample {
    double t;
    InputValue value;
  };
  std::map<std::string, std::vector<PoseSample>> poses_;    // sorted by t
  std::map<std::string, std::vector<ValueSample>> values_;  // sorted by t
  std::vector<ScriptEvent> events_;
};

}  // namespace pushpull::xrsim
