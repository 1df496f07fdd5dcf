#include "replay_session.hpp"
#include "drag_notes.hpp"
#include "region_camera.hpp"
#include "region_notes.hpp"

#include "commands.hpp"
#include "commit_watch.hpp"
#include "metrics_json.hpp"
#include "model_output.hpp"
#include "progress_bar.hpp"
#include "render_inputs.hpp"
#include "render_model.hpp"
#include "render_session.hpp"
#include "replay_report.hpp"
#include "review_loop.hpp"
#include "session_recorder.hpp"
#include "session_recording.hpp"
#include "sha256.hpp"

#include "pushpull/assets/model.hpp"
#include "pushpull/assets/write.hpp"
#include "pushpull/deform/mesh_io.hpp"
#include "pushpull/deform/metrics.hpp"
#include "pushpull/renderer/camera.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <regex>
#include <set>
#include <variant>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace pushpull::app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using json = nlohmann::json;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// .glb for glTF models (the scene with moved vertices), else the model's own mesh format (the welded mesh).
std::string model_extension(const std::string& model) {
  const std::string ext = lower(fs::path(model).extension().string());
  return (ext == ".gltf" || ext == ".glb" || ext == ".drc") ? ".glb" : ext;
}

// The replay's models: copies of the reviewed model's file where it is OFF/OBJ/PLY (model_output.hpp).
// Returns the notes that come with them (normals kept as they were, a layout written as triangles).
std::vector<std::string> write_model(const fs::path& path, const assets::Model& model,
                                     const Eigen::MatrixXd& V) {
  return write_deformed_model(path, model.source_path, model.deform_mesh, &model, V);
}

std::string two_digits(std::size_t i) {
  const std::string digits = std::to_string(i);
  return digits.size() < 2 ? "0" + digits : digits;
}

// The simulated runtime beside this executable (build/pushpull -> build/xr/sim/pushpull_xr_sim.json).
void point_at_simulated_runtime(const ReplayOptions& o, const SessionRecording& rec, const fs::path& script,
                                const fs::path& eyes) {
  if (std::getenv("XR_RUNTIME_JSON") == nullptr) {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    const fs::path manifest = exe.parent_path() / "xr" / "sim" / "pushpull_xr_sim.json";
    if (ec || !fs::exists(manifest))
      throw CommandError("no XR_RUNTIME_JSON set and no simulated runtime manifest at " + manifest.string() +
                         " (build the pushpull_xr_sim target, or set XR_RUNTIME_JSON to its manifest)");
    setenv("XR_RUNTIME_JSON", manifest.c_str(), 1);
  }
  const char* lavapipe = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";
  if (std::getenv("VK_ICD_FILENAMES") == nullptr && std::getenv("VK_DRIVER_FILES") == nullptr && fs::exists(lavapipe))
    setenv("VK_ICD_FILENAMES", lavapipe, 1);
  setenv("PUSHPULL_XR_SIM_INPUT", script.c_str(), 1);
  setenv("PUSHPULL_XR_SIM_CAPTURE", eyes.c_str(), 1);
  setenv("PUSHPULL_XR_SIM_CAPTURE_EVERY", std::to_string(std::max(0, o.capture_every)).c_str(), 1);
  setenv("PUSHPULL_XR_SIM_WIDTH", std::to_string(o.eye_size.at(0)).c_str(), 1);
  setenv("PUSHPULL_XR_SIM_HEIGHT", std::to_string(o.eye_size.at(1)).c_str(), 1);
  const long rate = rec.rate_hz > 0.0 ? std::lround(rec.rate_hz) : 90;
  setenv("PUSHPULL_XR_SIM_RATE", std::to_string(rate).c_str(), 1);
  if (!rec.profile.empty()) setenv("PUSHPULL_XR_SIM_PROFILE", rec.profile.c_str(), 1);
}

Eigen::Vector3d vec3(const json& j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }

// The recorded solver threshold `key` (an integer >= -1), -1 when the recording has none.
int recorded_threshold(const json& header, const char* key, const std::string& recording) {
  if (!header.contains("solver") || !header["solver"].is_object() || !header["solver"].contains(key))
    return -1;
  const json& value = header["solver"][key];
  if (!value.is_number_integer() || value.get<long long>() < -1 ||
      value.get<long long>() > std::numeric_limits<int>::max())
    throw CommandError(recording + ": solver." + key + " must be an integer >= -1, got " + value.dump());
  return value.get<int>();
}

// The names a replay writes in --out (and eyes/), and of those the ones it clears first: an earlier replay's
// commits and final model (it may have had more), and its report, which would otherwise outlive an
// interrupted replay and point at files no longer there. Exactly the names a replay gives them
// (commit-07.glb, commit-07-before.off, commit-07.metrics.json, commit-07-curvature.png, final.ply): a file
// of the user's that merely starts alike (commit-notes.txt, a recording named commit-session.jsonl) is left
// alone.
bool replay_clears(const std::string& name) {
  static const std::regex kNames(
      R"((commit-(0[1-9]|[1-9][0-9]+)(-before)?|final)\.(glb|off|obj|ply)|)"
      R"(commit-(0[1-9]|[1-9][0-9]+)\.metrics\.json|)"
      R"(commit-(0[1-9]|[1-9][0-9]+)-(before|after|displacement|curvature|curvature-before|reversals)\.png|report\.html)");
  return std::regex_match(name, kNames);
}
bool replay_writes(const std::string& name) {
  return replay_clears(name) || name == "input.jsonl" || name == "replay-session.jsonl";
}
// The eye images xr/sim captures into eyes/ (frame_000113_left.png).
bool replay_clears_eye_image(const std::string& name) {
  static const std::regex kNames(R"(frame_[0-9]{6,}_[a-z0-9-]+\.png)");
  return std::regex_match(name, kNames);
}

// The --out folder held for one replay: two replays writing into one folder at once mixed their recordings
// and reports (each then said "all checks passed"). An advisory lock on the folder itself (flock on its
// descriptor: nothing is left in the folder), released when the replay ends, however it ends.
class OutFolderLock {
 public:
  explicit OutFolderLock(const fs::path& folder)
      : fd_(::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    if (fd_ < 0)
      throw CommandError(folder.string() + ": cannot open the output folder (" + std::strerror(errno) + ")");
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      if (error == EWOULDBLOCK) {
        ::close(fd_);
        throw CommandError(
            folder.string() +
            ": another pushpull replay is writing into this folder; wait for it to end or give "
            "--out another folder");
      }
      // A file system that cannot lock a folder (NFS emulates flock with byte-range locks, which a folder
      // opened for reading cannot take): said, and the replay goes on unguarded.
      std::fprintf(
          stderr,
          "pushpull replay: warning: %s: cannot lock the folder against a second replay (%s); going on\n",
          folder.c_str(), std::strerror(error));
    }
  }
  OutFolderLock(const OutFolderLock&) = delete;
  OutFolderLock& operator=(const OutFolderLock&) = delete;
  ~OutFolderLock() { ::close(fd_); }

 private:
  int fd_;
};

// A .gltf's external files (its buffers' and images' URIs, data: URIs aside) beside it, read before the model
// is loaded (the replay clears its --out first): only their names are needed here; the load checks the rest.
std::vector<fs::path> external_files(const fs::path& model) {
  std::vector<fs::path> files;
  std::string extension = model.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension != ".gltf") return files;
  std::ifstream in(model);
  const json document = json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!document.is_object()) return files;
  for (const char* key : {"buffers", "images"}) {
    if (!document.contains(key) || !document[key].is_array()) continue;
    for (const json& entry : document[key])
      if (entry.is_object() && entry.contains("uri") && entry["uri"].is_string()) {
        const std::string uri = entry["uri"].get<std::string>();
        if (uri.rfind("data:", 0) != 0) files.push_back(model.parent_path() / uri);
      }
  }
  return files;
}

// A file the replay reads (the recording, the model) lying in --out under a name the replay writes or clears
// would be lost (a model renamed final.gltf was deleted before it was read): refused.
void refuse_inputs_in_out_folder(const fs::path& out,
                                 const std::vector<std::pair<fs::path, const char*>>& inputs) {
  std::error_code ec;
  const fs::path folder = fs::weakly_canonical(fs::absolute(out, ec), ec);
  for (const auto& [input, role] : inputs) {
    std::error_code error;
    const fs::path file = fs::weakly_canonical(fs::absolute(input, error), error);
    if (error) continue;
    const bool in_out = file.parent_path() == folder && replay_writes(file.filename().string());
    const bool in_eyes =
        file.parent_path() == folder / "eyes" && replay_clears_eye_image(file.filename().string());
    if (in_out || in_eyes)
      throw CommandError(input.string() + ": " + role + " lies in --out " + out.string() +
                         " under a name the " + "replay writes or clears (" + (in_eyes ? "eyes/" : "") +
                         file.filename().string() + "): give --out another folder");
  }
}

}  // namespace

void run_replay(const ReplayOptions& o) {
  const auto start = Clock::now();
  const SessionRecording rec = read_session_recording(o.recording);
  const json& header = rec.header;
  // --model, else the model where it was relative to the recording (a recording moved or checked out with its
  // model, as the bundled session), else the absolute path recorded.
  std::string model_path = o.model.empty() ? header.at("model").get<std::string>() : o.model;
  if (o.model.empty() && header.contains("model_relative")) {
    const fs::path beside = fs::path(o.recording).parent_path() / header["model_relative"].get<std::string>();
    if (std::error_code ec; fs::exists(beside, ec)) model_path = beside.lexically_normal().string();
  }
  if (model_path.empty())
    throw CommandError(o.recording + ":1: the header's \"model\" is empty; pass --model FILE");
  std::error_code status_error;
  const fs::file_status model_status = fs::status(model_path, status_error);
  if (status_error && status_error != std::errc::no_such_file_or_directory)
    throw CommandError(model_path + ": cannot read the " +
                       (o.model.empty() ? "recorded model file" : "--model file") + " (" +
                       status_error.message() + "; recording " + o.recording + ")");
  if (!fs::exists(model_status))
    throw CommandError(o.model.empty() ? model_path + ": the recorded model file does not exist (recording " +
                                             o.recording + "); pass --model FILE"
                                       : model_path + ": --model: no such file");
  if (fs::is_directory(model_status))
    throw CommandError(model_path + ": is a folder, not the recorded model file (recording " + o.recording +
                       ")");
  // Hashed whole: a device (/dev/zero) never ended.
  if (!fs::is_regular_file(model_status))
    throw CommandError(model_path + ": is not a regular file (a device or a pipe), not a model (recording " +
                       o.recording + ")");
  const std::string sha = sha256_file_hex(model_path);
  if (sha != header.at("model_sha256").get<std::string>())
    throw CommandError(model_path + ": SHA-256 " + sha + " differs from the recording's " +
                       header.at("model_sha256").get<std::string>() + " (" + o.recording +
                       " was made on another model file); refusing to replay");
  if (rec.cut) std::printf("pushpull replay: %s: %s; replaying up to the cut\n", o.recording.c_str(), rec.cut->c_str());

  if (o.out.empty()) throw CommandError("--out: an empty folder name");
  const fs::path out = o.out;
  {
    std::vector<std::pair<fs::path, const char*>> inputs{{o.recording, "the recording"},
                                                         {model_path, "the model"}};
    for (const fs::path& file : external_files(model_path))
      inputs.emplace_back(file, "a file the model reads");
    refuse_inputs_in_out_folder(out, inputs);
  }
  std::error_code ec;
  fs::create_directories(out, ec);  // (an error is said below, with eyes/)
  std::optional<OutFolderLock> lock;
  if (fs::is_directory(out, ec)) lock.emplace(out);  // before anything is written there
  fs::create_directories(out / "eyes", ec);
  if (ec)
    throw CommandError(out.string() + ": " +
                       (fs::is_directory(out) ? "cannot write into the output folder (its eyes/ folder): "
                                              : "cannot create the output folder: ") +
                       ec.message());
  // The eyes are captured by the runtime, which can only say on stderr that it could not write one: a folder
  // the replay cannot write into is refused here, before the session (it went on to "all checks passed" with
  // no eye images).
  for (const fs::path& folder : {out, out / "eyes"}) {
    const fs::path probe = folder / (".pushpull-replay-write-check-" + std::to_string(::getpid()));
    errno = 0;
    std::FILE* file = std::fopen(probe.c_str(), "wb");
    if (file == nullptr)
      throw CommandError(folder.string() + ": cannot write into it (" +
                         (errno != 0 ? std::strerror(errno) : "unknown error") + ")");
    std::fclose(file);
    fs::remove(probe, ec);
  }
  // What an earlier replay into the same folder wrote (it may have had more commits), said.
  std::size_t cleared = 0;
  for (const auto& [folder, clears] :
       {std::pair{out / "eyes", &replay_clears_eye_image}, std::pair{out, &replay_clears}}) {
    for (const auto& entry : fs::directory_iterator(folder)) {
      std::error_code error;
      if (entry.is_regular_file(error) && clears(entry.path().filename().string()) &&
          fs::remove(entry.path(), error))
        ++cleared;
    }
  }
  if (cleared > 0)
    std::printf(
        "pushpull replay: %s: removed %zu file(s) an earlier replay wrote (commit-NN*, final.*, "
        "report.html, eyes/frame_*.png); other files there are left alone\n",
        out.c_str(), cleared);

  // The script: the recording's complete lines, the eyes captured one frame after every release and at the
  // end, and the exit one frame after the last input.
  const double rate = rec.rate_hz > 0.0 ? rec.rate_hz : 90.0;
  const double frame = 1.0 / rate;
  std::string script = rec.script;
  std::vector<double> captures;
  std::vector<std::string> capture_captions;  // what each capture shows, for the report
  for (const json& r : rec.records)
    if (r.value("record", "") == "release") {
      captures.push_back(r.value("time", 0.0) + frame);
      capture_captions.push_back(
          "release " + std::to_string(captures.size()) +
          (r.value("committed", false) ? "" : ": the drag was cancelled, nothing committed"));
    }
  capture_captions.push_back("the end");
  // The end's: one frame after the last input, or, where the review recorded the runtime's exit, at the last
  // frame before it (the exit's frame shows nothing, and the session is gone after it).
  captures.push_back(rec.exit_time
                         ? std::max(0.0, std::min(rec.last_input_time + frame, *rec.exit_time - frame))
                         : rec.last_input_time + frame);
  for (const double t : captures) script += json{{"t", t}, {"event", "capture"}}.dump() + "\n";
  script += json{{"t", rec.last_input_time + 2.0 * frame}, {"event", "exit"}}.dump() + "\n";
  const fs::path script_path = out / "input.jsonl";
  deform::write_file_atomically(script_path, script);
  point_at_simulated_runtime(o, rec, script_path, out / "eyes");

  // The same review, from the header's options.
  const json& h = header.at("options");
  ReviewCommandOptions review;
  review.model = model_path;
  review.method = o.method.empty() ? h.at("method").get<std::string>() : o.method;
  review.fixed_method = !o.method.empty();
  // A review whose headset did not come back after a loss (no "resumed" record after its last "lost" one)
  // ended there: so does the replay, instead of its runtime coming back and saying "the headset is back".
  {
    bool lost_for_good = false;
    for (const json& r : rec.records) {
      const std::string kind = r.value("record", "");
      if (kind == "lost") lost_for_good = true;
      if (kind == "resumed") lost_for_good = false;
    }
    if (lost_for_good) review.reconnect_s = 0.0;
  }
  if (o.method.empty()) review.method_changes = rec.method_changes;  // with --method: that one throughout
  review.colour_changes = rec.colour_changes;
  review.size_changes = rec.size_changes;
  review.cancels = rec.cancels;
  review.history_steps = rec.history_steps;
  // How the recorded review behaved: its format's, or what a replay of an older one wrote down.
  if (rec.format_version > 0)
    review.behaviour_of_format =
        std::min(header.value("behaviour_format", rec.format_version), kNewestRecordingFormat);
  review.mu = o.mu.value_or(h.at("mu").get<double>());
  // Recordings made before the smooth start (and, from 2026-12-06, the coarse-to-fine start) existed solved
  // every cold start from rest: -1 when the key is missing.
  review.smooth_start_min_free = recorded_threshold(header, "smooth_start_min_free", o.recording);
  review.coarse_start_min_free = recorded_threshold(header, "coarse_start_min_free", o.recording);
  review.handle_radius_m = h.at("handle_radius_m");
  review.roi_radius_m = h.at("roi_radius_m");
  review.up = h.at("up").get<std::vector<double>>();
  review.up_given = true;
  review.front = h.at("front").get<std::vector<double>>();
  review.distance_m = h.at("distance_m");
  review.samples = 1;
  review.colour = h.value("colour", "displacement");
  review.life_size.scale = h.value("scale", 1.0);
  if (h.contains("length_m") && h["length_m"].is_number()) review.life_size.length_m = h["length_m"].get<double>();
  review.eye_size = o.eye_size;
  review.record = (out / "replay-session.jsonl").string();
  review.settle_drawn_frames = true;
  review.end_on_interrupt = false;
  review.press_holds = rec.press_holds;  // the same presses held back over the same frames
  review.recorded_anchor.emplace(rec.anchor);  // the model where the recorded review put it
  review.quiet = true;  // the replay prints its own line per commit
  // No display paces a replay: its loop runs flat out on the virtual clock, and a niced solver would crawl behind
  // it (the loop waits for the solver wherever results matter anyway).
  review.solver_nice = 0;
  review.solver_idle = false;
  review.solver_cpus = "none";
  if (o.capture_every <= 0)  // draw only the frames xr/sim captures (frame times are n / rate)
    review.draw_frame = [captures, frame](double t) {
      return std::any_of(captures.begin(), captures.end(), [&](double c) { return std::abs(t - c) < 0.5 * frame; });
    };
  const std::string ext = model_extension(model_path);
  review.out = (out / ("final" + ext)).string();
  // Hashes are compared for the commits solved as they were recorded: the same method as that commit's (a
  // session may switch methods on the way, and --method replays every commit with one) and the same mu.
  const bool same_mu = review.mu == header.at("options").at("mu").get<double>();
  const bool same_solver = o.method.empty() && same_mu;  // every push/pull solved as recorded
  // Desktop recordings replay the same way: the desktop loop fed its mouse gesture through the float aim pose
  // it recorded (hand_sample.hpp), so p0, d and the commits are bit-identical here too.
  const bool desktop = h.value("desktop", false);
  const double d_tolerance = 1e-9;  // model units
  // Metres per model unit as the review had it (from --length, or --scale), for lengths printed at life size.
  const double life_size_scale = header.value("life_size_scale", h.value("scale", 1.0));
  // A recording from a newer version may hold records this one does not know (they are left out).
  if (rec.format_version == 0 || rec.format_version > kNewestRecordingFormat)
    std::fprintf(
        stderr,
        "pushpull replay: warning: %s is in format '%s', this version knows pushpull-session-1 to -%d: "
        "records it does not know are left out, so the replay may differ\n",
        o.recording.c_str(), header.value("format", std::string("?")).c_str(), kNewestRecordingFormat);
  if (desktop)
    std::printf("pushpull replay: a desktop-mode recording: its mouse gestures replay as the right hand's aim ray "
                "and trigger\n");

  assets::Model model;
  try {
    model = assets::load_model(model_path);
  } catch (const std::exception& e) {
    throw CommandError(e.what());
  }
  {
    // The header's life-size scale is the review's --length over the model's longest side, or its --scale:
    // any other (1e308 printed |d| inf mm and NaN into the report) is a damaged header.
    const double longest = model.bounds.isEmpty() ? 0.0 : model.bounds.sizes().maxCoeff();
    const double expected = h.contains("length_m") && h["length_m"].is_number() && longest > 0.0
                                ? h["length_m"].get<double>() / longest
                                : h.value("scale", 1.0);
    if (!(std::abs(life_size_scale / expected - 1.0) <= 1e-6))
      throw CommandError(o.recording + ":1: the header's \"life_size_scale\" " +
                         json(life_size_scale).dump() + " is not the review's (" + json(expected).dump() +
                         (h.contains("length_m") && h["length_m"].is_number()
                              ? ": its length_m over the model's "
                                "longest side)"
                              : ": its scale)") +
                         "; the header is damaged");
  }
  ProgressBar bar;
  std::vector<CommitRecord> commits;
  std::vector<std::string> checks;  // per commit: how it compared with the recording
  std::string first_mismatch;
  const std::size_t recorded = rec.commits.size();
  // The recorded commit of a replayed one: every committed release ends as a commit or a failed commit, in
  // release order, in the recording as in the replay; the k-th outcome of the replay pairs with the k-th
  // recorded one (so a push/pull another --method could not commit shifts no later pairing). A recorded
  // release's outcome is the commit record of its request; none is a failed commit (recordings before the
  // "commit failed" record have them too), unless the recording was cut before it could say.
  std::vector<std::optional<std::size_t>> recorded_outcomes = release_outcomes(rec);
  // A cut recording's last releases may have lost their commit records: unknown, as after its end.
  if (rec.cut)
    while (!recorded_outcomes.empty() && !recorded_outcomes.back()) recorded_outcomes.pop_back();
  const std::size_t recorded_failures =
      rec.cut ? 0 : std::size_t(std::count(recorded_outcomes.begin(), recorded_outcomes.end(), std::nullopt));
  // Recordings whose releases carry no requests pair commits by index.
  if (recorded_outcomes.empty())
    for (std::size_t k = 0; k < recorded; ++k) recorded_outcomes.push_back(k);
  std::size_t outcomes = 0;  // the replay's so far
  // Hashes are compared while the replay's model is the recorded one: every commit before was solved with
  // its recorded method and mu and matched, and every push/pull the recording committed was committed.
  bool on_recorded_path = true;
  std::size_t failed_where_committed = 0;         // replay failures whose recorded push/pull was committed
  std::vector<std::optional<std::size_t>> pairs;  // per replayed commit: its recorded commit
  review.on_commit = [&](const CommitRecord& c) {
    commits.push_back(c);
    const fs::path file = out / ("commit-" + two_digits(c.index) + ext);
    // The notes are the model file's, the same for every commit: said with the first.
    for (const std::string& note : write_model(file, model, *c.snapshot->positions))
      if (c.index == 1) bar.print("pushpull replay: warning: " + note);
    std::string check;
    const std::size_t slot = outcomes++;
    const std::optional<std::size_t> pair =
        slot < recorded_outcomes.size() ? recorded_outcomes[slot] : std::nullopt;
    pairs.push_back(pair);
    if (!pair) {
      const bool beyond = outcomes > recorded_outcomes.size();
      check = beyond ? "not compared (after the end of the recording)"
                     : "not compared (the recording could not commit this push/pull)";
      if (!beyond && same_solver && first_mismatch.empty())
        first_mismatch = "commit " + std::to_string(c.index) + " was not committed in the recording";
      // Past the commits of a recording that ended (its end record there, not cut): one the review never
      // made.
      if (beyond && !rec.cut && same_solver && first_mismatch.empty())
        first_mismatch = "commit " + std::to_string(c.index) + " is one more than the recording's " +
                         std::to_string(recorded_outcomes.size()) + " (the review did not make it)";
      on_recorded_path = false;
    } else {
      const json& r = rec.commits[*pair].record;
      const std::size_t line = rec.commits[*pair].line;
      const std::string recorded_method =
          r.value("method", header.at("options").at("method").get<std::string>());
      const bool as_recorded =
          same_mu && lower(recorded_method) == lower(std::string(deform::method_name(c.snapshot->method)));
      const double gap = r.contains("d") ? (vec3(r["d"]) - c.snapshot->d).norm() : 0.0;
      if (same_solver && !as_recorded) {
        // Every push/pull is solved as recorded unless --method or --mu says otherwise: a method that
        // differs from the commit record's is the replay's (or the recording's) mistake, not a choice.
        on_recorded_path = false;
        check = "MISMATCH (method)";
        if (first_mismatch.empty())
          first_mismatch = "commit " + std::to_string(c.index) + " (recording line " + std::to_string(line) +
                           "): solved with " + std::string(deform::method_name(c.snapshot->method)) +
                           ", recorded with " + recorded_method;
      } else if (as_recorded && on_recorded_path) {
        check = r.at("hash") == hash_text(c.hash) ? "match" : "MISMATCH";
        on_recorded_path = check == "match";
        if (check != "match" && first_mismatch.empty())
          first_mismatch = "commit " + std::to_string(c.index) + " (recording line " + std::to_string(line) +
                           "): hash " + hash_text(c.hash) + " differs from the recorded " +
                           r.at("hash").get<std::string>() + " (tolerance: bit-identical positions)";
        // The same positions from another d: the commit record itself is damaged.
        if (check == "match" && gap > d_tolerance) {
          check = "MISMATCH (d)";
          if (first_mismatch.empty()) {
            char text[128];
            std::snprintf(text, sizeof text,
                          "d differs from the recorded one by %.3g model units (tolerance %.3g)", gap,
                          d_tolerance);
            first_mismatch = "commit " + std::to_string(c.index) + " (recording line " +
                             std::to_string(line) + "): its hash matches but " + text;
          }
        }
      } else {
        on_recorded_path = false;
        check = gap <= d_tolerance ? "match (d)" : "MISMATCH (d)";
        if (gap > d_tolerance && first_mismatch.empty()) {
          char text[160];
          std::snprintf(text, sizeof text, "d differs from the recorded one by %.3g model units (tolerance %.3g)",
                        gap, d_tolerance);
          first_mismatch =
              "commit " + std::to_string(c.index) + " (recording line " + std::to_string(line) +
              "): " + text +
              "; hashes are compared only for commits solved as recorded from the recorded model";
        }
      }
    }
    checks.push_back(check);
    char line[320], of[48];
    // "3/3"; past the recording's count (a recording short of commit records): "4 (of 3 recorded)".
    std::snprintf(of, sizeof of, c.index <= recorded ? "%zu/%zu" : "%zu (of %zu recorded)", c.index,
                  recorded);
    std::snprintf(line, sizeof line,
                  "pushpull replay: commit %s  |d| %.1f mm  %d it  %s  hash %s  %s  (%.1f s)", of,
                  1000.0 * life_size_scale * c.snapshot->d.norm(), c.snapshot->iteration,
                  c.snapshot->converged ? "converged" : "not converged", hash_text(c.hash).c_str(),
                  check.c_str(), seconds_since(start));
    bar.print(line);
  };
  // Push/pulls the solver could not commit: each is said, and the replay must fail as many as the recording.
  std::vector<std::string> not_committed;
  review.on_failed_commit = [&](const FailedCommit& f) {
    const std::size_t k = outcomes++;
    if (k < recorded_outcomes.size() && recorded_outcomes[k]) {
      ++failed_where_committed;
      on_recorded_path = false;
    }
    // Named by its place among the session's releases, with the commit before it: the report's "Push/pull N"
    // are its commits, which this is not (a failed release 2 and the committed push/pull 2 read as one).
    const std::string which =
        "release " + std::to_string(k + 1) + " of the recording (after " +
        (commits.empty() ? std::string("no commit") : "commit " + std::to_string(commits.size())) + ")";
    not_committed.push_back(which + ": " + f.error);
    bar.print("pushpull replay: " + which + " not committed (the model stays as it was): " + f.error);
  };
  // The bar follows the recording's virtual clock through the loop, then the report's commits.
  const double total_s = std::max(rec.last_input_time, 1e-9);
  review.on_frame = [&](double t) {
    char text[160];
    std::snprintf(text, sizeof text, "replaying %.1f / %.1f s of the session, %zu of %zu commit(s)", t, total_s,
                  commits.size(), recorded);
    bar.update(t / total_s, text);
  };
  const auto loop_start = Clock::now();
  run_review(review);
  const double loop_s = seconds_since(loop_start);
  // (Compared when every push/pull is solved as recorded: another --method or --mu may fail others.)
  if (same_solver && not_committed.size() != recorded_failures && first_mismatch.empty() && !rec.cut)
    first_mismatch = std::to_string(not_committed.size()) +
                     " push/pull(s) could not be committed in the replay, " +
                     std::to_string(recorded_failures) + " in the recording";
  // Every recorded commit reproduced; with another --method or --mu, those it could not commit excepted.
  std::vector<char> paired(recorded, 0);
  for (const auto& pair : pairs)
    if (pair) paired[*pair] = 1;
  const std::size_t unpaired = std::size_t(std::count(paired.begin(), paired.end(), 0));
  if (unpaired > (same_solver ? 0 : failed_where_committed) && first_mismatch.empty()) {
    const std::size_t k = std::size_t(std::find(paired.begin(), paired.end(), 0) - paired.begin());
    first_mismatch = "commit " + std::to_string(k + 1) + " (recording line " +
                     std::to_string(rec.commits[k].line) + ") was not reproduced (the replay made " +
                     std::to_string(commits.size()) + " of " + std::to_string(recorded) + " commits)";
  }

  // Metrics, pictures and the report.
  const auto report_start = Clock::now();
  // The pictures: one renderer for the whole report (render_session.hpp), the model uploaded once.
  std::shared_ptr<const RenderModel> render_model;
  std::optional<PictureRenderer> pictures;
  if (o.pictures && !commits.empty()) {
    try {
      render_model = std::make_shared<const RenderModel>(build_render_model(model));
      pictures.emplace(render_model, 1, false);
    } catch (const std::exception& e) {
      bar.print(std::string("pushpull replay: warning: the report's pictures are left out: ") + e.what());
    }
  }
  const double scale = life_size_scale;
  std::vector<ReportCommit> report;
  for (const CommitRecord& c : commits) {
    bar.update(double(c.index - 1) / double(commits.size()),
               "report: metrics and pictures of commit " + std::to_string(c.index) + " of " +
                   std::to_string(commits.size()),
               true);
    const deform::Snapshot& s = *c.snapshot;
    const deform::Mesh& before_mesh = c.before ? *c.before : model.deform_mesh;
    const std::string stem = "commit-" + two_digits(c.index);
    std::vector<int> roi;
    if (s.region) {
      roi.insert(roi.end(), s.region->handle.begin(), s.region->handle.end());
      roi.insert(roi.end(), s.region->fixed.begin(), s.region->fixed.end());
      roi.insert(roi.end(), s.region->free.begin(), s.region->free.end());
      std::sort(roi.begin(), roi.end());
    }
    DeformRunRecord record;
    // The file holding the shape this commit was solved from (so that `pushpull deform` on it repeats the
    // commit from its metrics): the model for the first commit (or after undoing every one), else the latest
    // earlier commit's file with the same positions (its hash), else one written for it, commit-NN-before.
    // (Absolute, as the model's, so that a deform run from any folder finds it.)
    record.input = std::filesystem::absolute(model_path).string();
    if (c.before) {
      const std::uint64_t before_hash = deform::position_hash(c.before->V);
      std::string found;
      for (const CommitRecord& earlier : commits)
        if (earlier.index < c.index && earlier.hash == before_hash)
          found = "commit-" + two_digits(earlier.index) + ext;
      if (found.empty() && before_hash != deform::position_hash(model.deform_mesh.V)) {
        found = stem + "-before" + ext;
        if (!pictures) (void)write_model(out / found, model, c.before->V);  // (with pictures: written below)
      }
      if (!found.empty()) record.input = std::filesystem::absolute(out / found).string();
    }
    record.output = stem + ext;
    record.options.method = s.method;
    record.options.mu = review.mu;
    if (review.smooth_start_min_free) record.options.smooth_start_min_free = *review.smooth_start_min_free;
    if (review.coarse_start_min_free) record.options.coarse_start_min_free = *review.coarse_start_min_free;
    record.d = s.d;
    // How the region was asked for: the press's surface point and radii, in model units (`pushpull deform
    // --handle-at P --handle-radius R --roi-radius M` repeats it with these times life_size_scale: its
    // command line takes metres at life size).
    if (s.committed_request) {
      if (const auto* handle = std::get_if<deform::SurfaceHandle>(&s.committed_request->handle)) {
        record.handle_at = handle->point.point;
        record.handle_radius = handle->radius;
      }
      if (std::isfinite(s.committed_request->region.max_distance))
        record.roi_radius = s.committed_request->region.max_distance;
    }
    record.vertices = long(s.positions->rows());
    if (s.region) {
      record.handle_count = long(s.region->handle.size());
      record.fixed_count = long(s.region->fixed.size());
      record.free_count = long(s.region->free.size());
    }
    record.result.iterations = s.iteration;
    record.result.converged = s.converged;
    // The snapshot does not carry the stop reason: with energy_tolerance 0 (the review's), converged means the
    // error tolerance was met.
    record.result.stop_reason = s.converged ? deform::StopReason::ErrorTolerance : deform::StopReason::MaxIterations;
    record.result.error_estimate = s.error_estimate;
    record.result.estimate_rate = s.estimate_rate;
    record.result.contraction_rate = s.contraction_rate;
    record.result.probe_rate = s.probe_rate;
    record.result.probe_evaluations = s.probe_evaluations;
    record.result.smooth_start = s.smooth_start;
    record.result.coarse_start = s.coarse_start;
    record.result.coarse_evaluations = s.coarse_evaluations;
    // The commit's own costs: setup and factorization read 0 when the drag's previews had built them.
    record.result.timing.precompute = s.setup_ms;
    record.result.timing.factorize = s.factorize_ms;
    record.result.timing.solve = s.solve_ms;
    record.result.timing.per_iteration = s.per_iteration_ms;     // the solve's, its start's time left out
    record.total_ms = s.setup_ms + s.factorize_ms + s.solve_ms;  // the commit's solve (no file reading here)
    record.dead_band_fraction = deform::MetricsOptions{}.flat_band;  // the band the metrics below use
    record.result.warnings = s.warnings;
    // What `pushpull deform` says of the same region (a whole part moved, a handle torn out) and pull (steep,
    // as the readout said it during the drag).
    if (s.region)
      if (const std::optional<UnheldRegion> unheld = unheld_region(*s.region))
        record.result.warnings.insert(record.result.warnings.begin(), unheld_region_text(*unheld));
    if (record.handle_at)
      if (const auto steep = steep_pull_warning(s.d.norm(), record.handle_radius))
        record.result.warnings.insert(record.result.warnings.begin(), *steep);
    if (s.energy_trace) record.result.energy_trace = *s.energy_trace;
    record.result.initial_energy = s.initial_energy;
    // The parts bound to the surface, each with how far it moved (as `pushpull deform` reports them).
    for (const deform::AttachedPart& part : s.attached) {
      double moved = 0.0;
      for (const int v : part.vertices)
        if (v < before_mesh.V.rows() && v < s.positions->rows())
          moved = std::max(moved, (s.positions->row(v) - before_mesh.V.row(v)).norm());
      if (!part.vertices.empty())
        record.attached.push_back({part.component, static_cast<long>(part.vertices.size()),
                                   part.vertices.front(), part.rest_gap, moved});
    }
    record.attach_reach = s.attach_reach;
    record.life_size_scale = scale;
    ReportCommit rc;
    if (s.d.norm() > 0.0 && !roi.empty()) {
      try {
        // Three section planes perpendicular to d, spread across the region's extent along d (as deform's).
        deform::MetricsOptions metrics_options;
        const Eigen::Vector3d unit = s.d.normalized();
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const int i : roi) {
          lo = std::min(lo, before_mesh.V.row(i).dot(unit));
          hi = std::max(hi, before_mesh.V.row(i).dot(unit));
        }
        for (int k = 1; k <= 3; ++k) metrics_options.section_offsets.push_back(lo + (hi - lo) * k / 4.0);
        record.metrics = deform::evaluate_deformation(before_mesh, *s.positions, s.d, roi, metrics_options);
      } catch (const std::exception& e) {
        record.result.warnings.push_back(std::string("metrics: ") + e.what());
      }
    }
    deform::write_file_atomically(out / (stem + ".metrics.json"), metrics_json(record));
    rc.index = c.index;
    rc.method = std::string(deform::method_name(s.method));
    rc.d_mm = 1000.0 * scale * s.d.norm();
    rc.iterations = s.iteration;
    rc.converged = s.converged;
    rc.error_estimate = s.error_estimate;
    rc.region_vertices = roi.size();
    rc.handle_vertices = std::size_t(std::max(0L, record.handle_count));
    if (record.handle_at) rc.handle_radius_mm = 1000.0 * scale * record.handle_radius;
    rc.p0 = record.handle_at;
    if (record.roi_radius) rc.roi_radius_mm = 1000.0 * scale * *record.roi_radius;
    if (s.committed_request && s.d.norm() > 0.0)
      if (const auto* handle = std::get_if<deform::SurfaceHandle>(&s.committed_request->handle)) {
        const int f = handle->point.face;
        if (f >= 0 && f < model.deform_mesh.F.rows()) {
          const auto corner = [&](int k) {
            return Eigen::Vector3d(before_mesh.V.row(model.deform_mesh.F(f, k)).transpose());
          };
          const Eigen::Vector3d normal = (corner(1) - corner(0)).cross(corner(2) - corner(0));
          if (normal.norm() > 0.0)
            rc.angle_to_normal_deg =
                std::acos(std::min(1.0, std::abs(normal.normalized().dot(s.d.normalized())))) * 180.0 /
                std::numbers::pi;
        }
      }
    rc.warnings = record.result.warnings;
    rc.attached_parts = s.attached_parts;
    rc.attached_moved =
        std::size_t(std::count_if(record.attached.begin(), record.attached.end(),
                                  [](const AttachedPartRecord& a) { return a.max_displacement > 0.0; }));
    rc.metrics = record.metrics;
    rc.d = s.d;
    rc.scale = scale;
    if (review.up.size() == 3) rc.up = Eigen::Vector3d(review.up[0], review.up[1], review.up[2]);
    rc.hash = hash_text(c.hash);
    if (const auto pair = pairs.at(c.index - 1)) rc.recorded_hash = rec.commits[*pair].record.at("hash");
    rc.check = checks.at(c.index - 1);
    if (rc.check == "match") rc.check = "match: bit-identical to the recording";
    rc.model_file = stem + ext;
    rc.metrics_file = stem + ".metrics.json";
    if (pictures) {
      const std::string before = stem + "-before" + ext;
      (void)write_model(out / before, model, before_mesh.V);  // (its notes said with commit 1's)
      const Eigen::Vector3d p0 = s.region && !s.region->handle.empty()
                                     ? Eigen::Vector3d(before_mesh.V.row(s.region->handle.front()).transpose())
                                     : Eigen::Vector3d::Zero();
      const Eigen::Vector3d p1 = p0 + s.d;
      const deform::Mesh before_shape{before_mesh.V,
                                      model.deform_mesh.F};  // the pictures' rest, the camera's
      RenderCommandOptions base;
      base.size = o.picture_size;
      base.samples = 1;
      base.up = review.up;
      // Looking at the push/pull's region (before and after), from outside along the surface at p0.
      if (s.region && !s.region->handle.empty() && review.up.size() == 3) {
        std::vector<int> region = s.region->handle;
        region.insert(region.end(), s.region->free.begin(), s.region->free.end());
        region.insert(region.end(), s.region->fixed.begin(), s.region->fixed.end());
        if (const auto camera =
                region_camera(before_shape, *s.positions, region, s.region->handle.front(),
                              Eigen::Vector3d(review.up[0], review.up[1], review.up[2]), base.fov_deg)) {
          base.eye = {camera->eye.x(), camera->eye.y(), camera->eye.z()};
          base.target = {camera->target.x(), camera->target.y(), camera->target.z()};
        }
      }
      struct Picture {
        std::string caption, file, color;
        bool after, arrow;
      };
      const std::vector<Picture> list{
          {"before", stem + "-before.png", "material", false, false},
          {"after", stem + "-after.png", "material", true, true},
          // The colour map's top at |d|, as the paper's Fig. 1 sets dist_max = |d|: the same colour is the
          // same move in every commit and every method of a --compare (a vertex moved more than |d| is red).
          {"displacement (this push/pull; red at |d| or more)", stem + "-displacement.png", "displacement",
           true, true},
          // Before beside after, as the paper's Fig. 12 compares them: where a sign reversed shows.
          {"Gaussian curvature sign before", stem + "-curvature-before.png", "curvature-sign", false, false},
          {"Gaussian curvature sign after", stem + "-curvature.png", "curvature-sign", true, false},
          // Where the two differ by a reversal (the metrics' "sign reversals"), in the new sign's colour.
          {"where the curvature sign reversed", stem + "-reversals.png", "curvature-reversal", true, false}};
      // Prepared first, then drawn from one camera framing before and after (a push/pull that grows the
      // model used to move the whole after picture against the before one).
      std::vector<std::optional<std::pair<RenderInputs, RenderCommandOptions>>> prepared;
      std::optional<std::pair<glm::vec3, glm::vec3>> frame;
      for (const Picture& picture : list) {
        RenderCommandOptions po = base;
        po.color = picture.color;
        if (picture.arrow) po.arrow = {p0.x(), p0.y(), p0.z(), p1.x(), p1.y(), p1.z()};  // file units
        if (picture.color == "displacement" && s.d.norm() > 0.0) po.scalar_max = s.d.norm();  // file units
        try {
          // The before shape is the original model's for the first commit, a deformed one after.
          const bool moved = picture.after || c.before != nullptr;
          RenderInputs inputs = prepare_render_inputs(
              render_model, before_shape, picture.after ? *s.positions : before_mesh.V, moved, po, scale);
          const renderer::Bounds box = renderer::compute_bounds(inputs.positions);
          frame = frame ? std::pair{glm::min(frame->first, box.min), glm::max(frame->second, box.max)}
                        : std::pair{box.min, box.max};
          prepared.emplace_back(std::pair{std::move(inputs), po});
        } catch (const std::exception& e) {
          prepared.emplace_back();
          bar.print("pushpull replay: warning: the " + picture.caption + " picture of commit " +
                    std::to_string(c.index) + " failed: " + e.what());
        }
      }
      for (std::size_t k = 0; k < list.size(); ++k) {
        if (!prepared[k]) continue;
        auto& [inputs, po] = *prepared[k];
        inputs.frame = frame;
        try {
          write_picture(out / list[k].file, pictures->render(inputs, po));
          rc.pictures.push_back({list[k].caption, list[k].file});
        } catch (const std::exception& e) {
          bar.print("pushpull replay: warning: the " + list[k].caption + " picture of commit " +
                    std::to_string(c.index) + " failed: " + e.what());
        }
      }
    }
    report.push_back(std::move(rc));
    char line[128];
    std::snprintf(line, sizeof line, "pushpull replay: report %zu/%zu (%.1f s)", report.size(), commits.size(),
                  seconds_since(start));
    bar.print(line);
    std::fflush(stdout);
  }
  ReportSession session;
  session.recording = o.recording;
  session.model = model_path;
  session.model_sha256 = sha;
  session.runtime = header.value("runtime", "");
  session.method = review.method;
  session.mu = review.mu;
  session.cut = rec.cut.value_or("");
  {  // What the session's undo and redo left: the report marks the push/pulls the final model does not hold.
    // From the replay's own recording: its commits are the report's (with --method one may fail where the
    // recorded one did not, and a recording cut before a commit landed has the replay make it).
    CommitHistory history;
    try {
      const SessionRecording replayed = read_session_recording(review.record);
      history = commit_history(replayed);
      // The session's end: what undo and redo left, against the recorded end (the commits compare each
      // commit; only this compares the model the session ended with). Where every push/pull was solved as
      // recorded and the recording was not cut.
      auto end_of = [](const SessionRecording& r) -> const json* {
        for (auto it = r.records.rbegin(); it != r.records.rend(); ++it)
          if (it->value("record", "") == "end") return &*it;
        return nullptr;
      };
      const json* recorded_end = end_of(rec);
      const json* replayed_end = end_of(replayed);
      if (same_solver && !rec.cut && first_mismatch.empty() && recorded_end != nullptr &&
          replayed_end != nullptr && recorded_end->contains("hash") && replayed_end->contains("hash")) {
        const json recorded_commits = recorded_end->value("commits", json());
        const json replayed_commits = replayed_end->value("commits", json());
        auto text = [](const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); };
        if ((*recorded_end)["hash"] != (*replayed_end)["hash"] || recorded_commits != replayed_commits)
          first_mismatch =
              "the session's end (recording line " + std::to_string(recorded_end->value("line", 0)) +
              "): the final model has hash " + text((*replayed_end)["hash"]) + " after " +
              text(replayed_commits) + " commit(s), recorded " + text((*recorded_end)["hash"]) + " after " +
              text(recorded_commits) + " (the undos and redos went otherwise, or the end record is damaged)";
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr,
                   "pushpull replay: warning: %s: %s; the report does not say which push/pulls were undone\n",
                   review.record.c_str(), e.what());
    }
    const bool stepped = std::any_of(history.steps.begin(), history.steps.end(), [](const std::string& s) {
      return s == "undo" || s == "redo" || s == "a drag cancelled";
    });
    if (stepped) {
      for (std::size_t k = 0; k < history.steps.size(); ++k)
        session.history += (k ? ", " : "") + history.steps[k];
      session.final_model =
          history.kept.empty() ? "the model as loaded (every push/pull undone)" : "push/pull ";
      for (std::size_t k = 0; k < history.kept.size(); ++k)
        session.final_model += (k ? ", " : "") + std::to_string(history.kept[k]);
      for (ReportCommit& c : report)
        c.undone = std::find(history.kept.begin(), history.kept.end(), c.index) == history.kept.end();
    }
  }
  std::set<std::string> eyes;
  for (const auto& entry : fs::directory_iterator(out / "eyes"))
    if (replay_clears_eye_image(entry.path().filename().string()))  // the captures, not a user's own files
      eyes.insert("eyes/" + entry.path().filename().string());
  session.eye_images.assign(eyes.begin(), eyes.end());
  // Each capture's caption: the release (or the end) whose time it was taken one frame after. The frame
  // number in the file name is xr/sim's, frame n at n / rate; within a frame and a half of a capture time.
  for (const std::string& file : session.eye_images) {
    std::string caption = file;
    long long number = 0;
    if (std::sscanf(file.c_str(), "eyes/frame_%lld_", &number) == 1)
      for (std::size_t k = 0; k < captures.size() && k < capture_captions.size(); ++k)
        if (std::abs(double(number) * frame - captures[k]) <= 1.5 * frame) {
          caption = capture_captions[k] + " (" + file + ")";
          break;
        }
    session.eye_captions.push_back(caption);
  }
  session.not_committed = not_committed;
  // Commits with no recorded commit to compare with (a recording cut inside a commit's line).
  const auto not_compared = std::size_t(std::count(pairs.begin(), pairs.end(), std::nullopt));
  const auto past_the_end = std::size_t(std::count_if(checks.begin(), checks.end(), [](const std::string& c) {
    return c.rfind("not compared (after the end", 0) == 0;
  }));
  session.summary =
      std::to_string(commits.size()) + " commit(s) replayed of " + std::to_string(recorded) + " recorded" +
      (not_compared == 0 ? std::string()
                         : ", " + std::to_string(not_compared) + " not compared with the recording" +
                               (rec.cut && past_the_end == not_compared ? " (past its cut)" : "")) +
      (not_committed.empty()
           ? std::string()
           : ", " + std::to_string(not_committed.size()) +
                 " push/pull(s) not committed (recorded: " + std::to_string(recorded_failures) + ")") +
      "; " + (first_mismatch.empty() ? "all checks passed" : "first mismatch: " + first_mismatch);
  write_replay_report((out / "report.html").string(), session, report);
  bar.finish();
  std::printf("pushpull replay: %s; time: loop %.1f s, metrics and pictures %.1f s, total %.1f s\n",
              session.summary.c_str(), loop_s, seconds_since(report_start), seconds_since(start));
  if (!session.final_model.empty())
    std::printf("pushpull replay: final model: %s (history: %s)\n", session.final_model.c_str(),
                session.history.c_str());
  std::printf("pushpull replay: report %s\n", (out / "report.html").c_str());
  if (rec.cut) std::printf("pushpull replay: replayed up to the cut: %s\n", rec.cut->c_str());
  if (!first_mismatch.empty()) throw CommandError(o.recording + ": replay mismatch at " + first_mismatch);
}

}  // namespace pushpull::app
