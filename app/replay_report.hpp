// The HTML report of a replay (report.html beside the pictures it shows): the session (model, SHA-256,
// method, runtime), then per push/pull: before / after pictures, displacement and curvature-sign maps,
// method, |d| in life-size mm, iterations, converged, error estimate, curvature sign reversals and flips,
// displacement along and across d, the section curves before and after (inline SVG), the hash check; the
// session's undo and redo, and which push/pulls the final model holds (an undone one is marked so).
// Thread-safety: pure function of its arguments plus one file write.
#pragma once

#include "pushpull/deform/metrics.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace pushpull::app {

struct ReportCommit {
  std::size_t index = 0;
  std::string method;
  double d_mm = 0.0;  // |d| at life size
  int iterations = 0;
  bool converged = false;
  std::optional<double> error_estimate;
  std::size_t region_vertices = 0;   // the solved region (handle, free and fixed border)
  std::size_t handle_vertices = 0;   // of those, the handle's (moved by d)
  // How the press asked for them (life-size mm along the surface from p0); none where not recorded.
  std::optional<double> handle_radius_mm, roi_radius_mm;
  // The angle between d and the surface normal at p0 (degrees, 0-90: 0 a push or pull along the normal, 90
  // a drag along the surface); none where the press's face is unknown.
  std::optional<double> angle_to_normal_deg;
  std::size_t attached_parts = 0;    // separate parts bound to the surface (lamps, glass, trims)
  std::size_t attached_moved = 0;    // those of them the commit moved
  std::vector<std::string> warnings;   // the commit's (as in its metrics file)
  deform::DeformationMetrics metrics;  // with sections (plotted before / after)
  Eigen::Vector3d d = Eigen::Vector3d::Zero();  // model units: the sections' planes are perpendicular to it
  std::optional<Eigen::Vector3d> p0;            // the press's surface point (model units), where recorded
  double scale = 1.0;  // metres per model unit (metrics lengths are model units)
  // The model's up axis (model frame): the sections are drawn with it up where d is not along it.
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  std::string hash, recorded_hash;  // recorded_hash "" when not compared
  std::string check;                 // "match", "mismatch: ...", "not compared: ..."
  std::string model_file, metrics_file;
  std::vector<std::pair<std::string, std::string>> pictures;  // caption, file name (relative to the report)
  bool undone = false;  // taken back by the session's undo: not in the final model
};

struct ReportSession {
  std::string recording, model, model_sha256, runtime, method;
  double mu = 0.0;
  std::string cut;  // "" when the recording is complete
  std::vector<std::string> eye_images;  // file names relative to the report
  std::vector<std::string>
      eye_captions;  // per eye image: the release it shows ("release 2: the drag was ...")
  std::string summary;
  std::string history;      // the session's push/pulls, undos and redos in order ("" when none)
  std::string final_model;  // which push/pulls the final model is made of
  std::vector<std::string> not_committed;  // the errors of push/pulls the solver could not commit, in order
};

// Writes `path` atomically; throws CommandError naming it.
void write_replay_report(const std::string& path, const ReportSession& session,
                         const std::vector<ReportCommit>& commits);

}  // namespace pushpull::app
