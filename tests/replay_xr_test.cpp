// `pushpull review --record` and `pushpull replay` against the simulated OpenXR runtime (xr/sim) on lavapipe:
// a scripted drag is recorded (header with the model's SHA-256, input by OpenXR path, press/release/commit
// with hashes); replaying it reproduces every commit hash bit for bit and the same meshes twice; a truncated
// recording replays up to the cut and says so; another model (SHA-256 mismatch) is refused; a corrupted line
// is named by its number.
#include "command_runner.hpp"
#include "xr_sim_environment.hpp"

#include "pushpull/deform/mesh_io.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using pushpull::testing::run_command;

using pushpull::testing::kHood;
const std::string& kPlacement = pushpull::testing::kHoodPlacement;

fs::path test_dir() { return pushpull::testing::fresh_test_dir("pushpull_replay_xr_tests"); }

std::string sim_env() { return pushpull::testing::xr_sim_environment(); }

// Two drags on the bonnet (pull 100 mm towards the reviewer, then push 40 mm down), an undo and a redo, with
// the head and the hand as a script: 30 Hz virtual clock, 64x64 eyes, Touch controllers.
const char* kScript =
    R"({"t":0.0,"path":"/user/head","pose":{"p":[0,1.0,0],"q":[-0.32557,0,0,0.94552]}}
{"t":0.0,"path":"/user/hand/right/input/aim/pose","pose":{"p":[0.0123,0.5,-0.65],"q":[-0.70710678,0,0,0.70710678]}}
{"t":0.0,"path":"/user/hand/right/input/trigger/value","value":0.0}
{"t":0.3,"path":"/user/hand/right/input/aim/pose","pose":{"p":[0.0123,0.5,-0.65],"q":[-0.70710678,0,0,0.70710678]}}
{"t":0.3,"path":"/user/hand/right/input/trigger/value","value":1.0}
{"t":0.8,"path":"/user/hand/right/input/aim/pose","pose":{"p":[0.0123,0.5,-0.55],"q":[-0.70710678,0,0,0.70710678]}}
{"t":0.9,"path":"/user/hand/right/input/trigger/value","value":0.0}
{"t":1.0,"path":"/user/hand/right/input/aim/pose","pose":{"p":[0.0123,0.5,-0.55],"q":[-0.70710678,0,0,0.70710678]}}
{"t":1.8,"path":"/user/hand/right/input/aim/pose","pose":{"p":[0.1123,0.5,-0.95],"q":[-0.70710678,0.02,0,0.70710678]}}
{"t":1.9,"path":"/user/hand/right/input/trigger/value","value":1.0}
{"t":2.3,"path":"/user/hand/right/input/aim/pose","pose":{"p":[0.1123,0.46,-0.95],"q":[-0.70710678,0.02,0,0.70710678]}}
{"t":2.4,"path":"/user/hand/right/input/trigger/value","value":0.0}
{"t":2.6,"path":"/user/hand/right/input/a/click","value":1.0}
{"t":2.7,"path":"/user/hand/right/input/a/click","value":0.0}
{"t":2.8,"path":"/user/hand/right/input/b/click","value":1.0}
{"t":2.9,"path":"/user/hand/right/input/b/click","value":0.0}
{"t":3.2,"event":"exit"}
)";

std::vector<nlohmann::json> read_lines(const fs::path& file) {
  std::vector<nlohmann::json> out;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.push_back(nlohmann::json::parse(line));
  return out;
}

std::vector<nlohmann::json> records(const std::vector<nlohmann::json>& lines, const std::string& kind) {
  std::vector<nlohmann::json> out;
  for (const auto& j : lines)
    if (j.value("record", "") == kind) out.push_back(j);
  return out;
}

// Records kScript with `pushpull review --record dir/session.jsonl`, its frames paced in real time as a
// headset's are: the second press comes 1.0 s after the first release, time enough for the commit to land
// (its asan solve is probed: 0.4 s was too short with the tests running two at a time)
// (unpaced, the loop's virtual clock outruns the solver, and the press is held back for the whole drag).
// The solver runs at normal priority (--solver-priority 0): at the review's default (nice 10) any other busy
// process on the machine starved it, and with three beside ctest -j2 on 2 cores the first commit (170
// iterations) had not landed 2.6 s after its release, so the second press was lost in 4 of these 13 tests;
// at 0 they all pass with six.
fs::path record_script(const fs::path& dir, const std::string& script) {
  std::ofstream(dir / "script.jsonl") << script;
  const auto r = run_command(sim_env() + " PUSHPULL_XR_SIM_INPUT=" + (dir / "script.jsonl").string() +
                             " PUSHPULL_XR_SIM_WIDTH=64 PUSHPULL_XR_SIM_HEIGHT=64 PUSHPULL_XR_SIM_RATE=30"
                             " PUSHPULL_XR_SIM_PACE=1"
                             " PUSHPULL_XR_SIM_PROFILE=/interaction_profiles/oculus/touch_controller " +
                             PUSHPULL_EXECUTABLE + " review " + kHood + kPlacement +
                             " --solver-priority 0 --record " + (dir / "session.jsonl").string());
  EXPECT_EQ(r.status, 0) << r.output;
  return dir / "session.jsonl";
}
fs::path record_session(const fs::path& dir) {
  return record_script(dir, kScript);
}

pushpull::testing::CommandResult replay(const fs::path& recording, const fs::path& out,
                                        const std::string& extra = "") {
  return pushpull::testing::run_pushpull("replay " + recording.string() + " --out " + out.string() +
                                         " --eye-size 64 64 " + extra);
}

TEST(ReplayXr, RecordingHasHeaderInputAndDerivedEvents) {
  const fs::path dir = test_dir();
  const auto lines = read_lines(record_session(dir));
  ASSERT_FALSE(lines.empty());
  const nlohmann::json& header = lines.front();
  EXPECT_EQ(header.at("record"), "header");
  const auto sum = run_command("sha256sum " + kHood);  // coreutils: an independent SHA-256
  ASSERT_EQ(sum.status, 0) << sum.output;
  EXPECT_EQ(header.at("model_sha256").get<std::string>(), sum.output.substr(0, 64));
  EXPECT_EQ(header.at("method"), "asan");
  EXPECT_EQ(header.at("T_stage_model").size(), 16u);
  EXPECT_FALSE(header.at("runtime").get<std::string>().empty());
  EXPECT_EQ(records(lines, "profile").at(0).at("profile"), "/interaction_profiles/oculus/touch_controller");
  size_t aim = 0, trigger = 0;
  for (const auto& j : lines) {
    if (j.value("path", "") == "/user/hand/right/input/aim/pose") ++aim;
    if (j.value("path", "") == "/user/hand/right/input/trigger/value") ++trigger;
    if (j.contains("record")) {
      EXPECT_FALSE(j.contains("t")) << j.dump();  // xr/sim must skip derived records
    }
  }
  EXPECT_GE(aim, 75u);     // every frame of ~3.2 s at 30 Hz
  EXPECT_EQ(trigger, 5u);  // 0, 1, 0, 1, 0: only changes
  ASSERT_EQ(records(lines, "press").size(), 2u);
  ASSERT_EQ(records(lines, "release").size(), 2u);
  ASSERT_EQ(records(lines, "commit").size(), 2u);
  EXPECT_EQ(records(lines, "undo").size(), 1u);
  EXPECT_EQ(records(lines, "redo").size(), 1u);
  EXPECT_FALSE(records(lines, "drag").empty());
  const std::vector<double> d = records(lines, "release")[0].at("d");
  EXPECT_NEAR(d[1], -0.1, 1e-6);  // the hand moved 100 mm towards the reviewer: model -Y
  EXPECT_EQ(records(lines, "commit")[0].at("hash").get<std::string>().size(), 18u);
  EXPECT_EQ(records(lines, "end").at(0).at("hash"), records(lines, "commit")[1].at("hash"));
}

std::vector<std::string> text_lines(const fs::path& file) {
  std::vector<std::string> out;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

void write_lines(const fs::path& file, const std::vector<std::string>& lines) {
  std::ofstream out(file);
  for (const std::string& line : lines) out << line << '\n';
}

std::string file_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ReplayXr, ReplayReproducesEveryCommitHashAndTheSameMeshesTwice) {
  const fs::path dir = test_dir();
  const fs::path session = record_session(dir);
  const auto recorded = records(read_lines(session), "commit");
  ASSERT_EQ(recorded.size(), 2u);

  const auto first = replay(session, dir / "replay1");
  ASSERT_EQ(first.status, 0) << first.output;
  EXPECT_NE(first.output.find("2 commit(s) replayed of 2 recorded; all checks passed"), std::string::npos)
      << first.output;
  // The replay's own recording has the same commit hashes.
  const auto replayed = records(read_lines(dir / "replay1" / "replay-session.jsonl"), "commit");
  ASSERT_EQ(replayed.size(), 2u);
  for (size_t i = 0; i < 2; ++i) EXPECT_EQ(replayed[i].at("hash"), recorded[i].at("hash"));
  for (const char* file : {"commit-01.off", "commit-02.off", "final.off", "commit-01.metrics.json",
                           "commit-02.metrics.json", "report.html", "commit-02-displacement.png",
                           "commit-02-curvature-before.png", "commit-02-curvature.png"})
    EXPECT_TRUE(fs::exists(dir / "replay1" / file)) << file << "\n" << first.output;
  const auto metrics = nlohmann::json::parse(file_bytes(dir / "replay1" / "commit-01.metrics.json"));
  EXPECT_NEAR(double(metrics.at("d").at(1)), -0.1, 1e-6);
  EXPECT_GT(int(metrics.at("iterations")), 0);
  // How the region was asked for, as the press recorded it (the hood is in metres: model units = metres).
  const auto press = records(read_lines(session), "press").at(0);
  const nlohmann::json& region = metrics.at("region");
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(double(region.at("handle_at").at(k)), double(press.at("p0").at(k)), 1e-9) << region.dump();
  EXPECT_DOUBLE_EQ(double(region.at("handle_radius")), double(press.at("handle").at("radius")));
  EXPECT_DOUBLE_EQ(double(region.at("roi_radius")), double(press.at("roi_radius")));
  EXPECT_TRUE(region.at("handle_file").is_null());
  // Measured against the state before the commit (for commit 2: after commit 1), not the original model.
  EXPECT_NEAR(double(metrics.at("max_displacement")), 0.1, 1e-3);
  const auto metrics2 = nlohmann::json::parse(file_bytes(dir / "replay1" / "commit-02.metrics.json"));
  EXPECT_NEAR(double(metrics2.at("max_displacement")), std::abs(double(recorded[1].at("d").at(2))), 0.02);
  // Each commit's input is the file its shape was solved from: the model, then commit 1's (it named the
  // model for every commit, and a deform run repeated from commit 2's metrics solved another problem).
  EXPECT_EQ(metrics.at("input"), kHood);
  EXPECT_EQ(metrics2.at("input"), (dir / "replay1" / "commit-01.off").string());
  const std::string report = file_bytes(dir / "replay1" / "report.html");
  EXPECT_NE(report.find("Push/pull 2"), std::string::npos);
  EXPECT_NE(report.find("100.0 mm"), std::string::npos);
  EXPECT_NE(report.find("<polyline"), std::string::npos);  // the section curves
  // Seen along d, the cut before and the same surface points after, with the gap between them and a scale.
  EXPECT_NE(report.find("the same surface points after red, their move across d drawn x"), std::string::npos);
  EXPECT_NE(report.find(" mm across d, and along d from "), std::string::npos);
  EXPECT_NE(report.find(" p0 along d, seen along d"), std::string::npos);  // placed from the press
  EXPECT_NE(report.find(" mm</text>"), std::string::npos);  // the scale bar's length
  EXPECT_NE(report.find("How to read this report"), std::string::npos);
  EXPECT_NE(report.find("asan (ASAN: "), std::string::npos);  // the paper's name beside the option's
  // Each section's carried curve, point for point with its cut, in the commit's metrics.
  for (const auto& section : metrics.at("sections")) {
    ASSERT_EQ(section.at("carried").size(), section.at("before").size());
    for (std::size_t c = 0; c < section.at("before").size(); ++c)
      EXPECT_EQ(section.at("carried")[c].at("points").size(), section.at("before")[c].at("points").size());
  }
  // The committed model moved 100 mm at most, where the hand pulled.
  const auto rest = pushpull::deform::read_mesh(kHood);
  const auto one = pushpull::deform::read_mesh(dir / "replay1" / "commit-01.off");
  EXPECT_NEAR((one.V - rest.V).rowwise().norm().maxCoeff(), 0.1, 1e-3);

  const auto second = replay(session, dir / "replay2", "--no-pictures");
  ASSERT_EQ(second.status, 0) << second.output;
  for (const char* file : {"commit-01.off", "commit-02.off", "final.off"})
    EXPECT_EQ(file_bytes(dir / "replay1" / file), file_bytes(dir / "replay2" / file)) << file;
  // Both eyes one frame after each release and at the end, drawn once the solver settled: the same images.
  std::vector<fs::path> eyes;
  for (const auto& e : fs::directory_iterator(dir / "replay1" / "eyes")) eyes.push_back(e.path().filename());
  EXPECT_EQ(eyes.size(), 6u);  // 2 releases + the end, 2 eyes each
  for (const fs::path& eye : eyes)
    EXPECT_EQ(file_bytes(dir / "replay1" / "eyes" / eye), file_bytes(dir / "replay2" / "eyes" / eye)) << eye;
}

TEST(ReplayXr, AnotherMethodComparesDInsteadOfHashes) {
  const fs::path dir = test_dir();
  const auto r = replay(record_session(dir), dir / "arap", "--method arap-sr --no-pictures");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("match (d)"), std::string::npos) << r.output;
  EXPECT_NE(file_bytes(dir / "arap" / "commit-01.metrics.json").find("\"arap-sr\""), std::string::npos);
}

// A session that switched methods on the way (the headset's menu panel between its two push/pulls), replayed
// with --method asan: the commit made with asan is compared by hash, the one made with the other method by d,
// and the replay passes (it used to compare every commit with the header's method and fail on the second).
// Replayed with the other method, both are compared by d (the second starts from a model solved otherwise).
TEST(ReplayXr, AMethodSwitchedMidSessionIsComparedPerCommit) {
  const fs::path dir = test_dir();
  const std::string aim = R"("pose":{"p":[0.0123,0.5,-0.65],"q":[-0.70710678,0,0,0.70710678]})";
  const fs::path recording =
      record_script(dir, R"({"t":0.0,"path":"/user/head","pose":{"p":[0,1.0,0],"q":[-0.32557,0,0,0.94552]}}
{"t":0.0,"path":"/user/hand/right/input/aim/pose",)" +
                             aim + R"(}
{"t":0.0,"path":"/user/hand/right/input/trigger/value","value":0.0}
{"t":0.3,"path":"/user/hand/right/input/trigger/value","value":1.0}
{"t":0.8,"path":"/user/hand/right/input/aim/pose","pose":{"p":[0.0123,0.5,-0.55],"q":[-0.70710678,0,0,0.70710678]}}
{"t":0.9,"path":"/user/hand/right/input/trigger/value","value":0.0}
{"t":1.2,"path":"/user/hand/left/input/menu/click","value":1.0}
{"t":1.3,"path":"/user/hand/left/input/menu/click","value":0.0}
{"t":1.4,"path":"/user/hand/right/input/thumbstick","value":[0.0,1.0]}
{"t":1.5,"path":"/user/hand/right/input/thumbstick","value":[0.0,0.0]}
{"t":1.6,"path":"/user/hand/right/input/trigger/value","value":1.0}
{"t":1.7,"path":"/user/hand/right/input/trigger/value","value":0.0}
{"t":1.8,"path":"/user/hand/left/input/menu/click","value":1.0}
{"t":1.9,"path":"/user/hand/left/input/menu/click","value":0.0}
{"t":2.0,"path":"/user/hand/right/input/aim/pose","pose":{"p":[0.1123,0.5,-0.95],"q":[-0.70710678,0.02,0,0.70710678]}}
{"t":2.2,"path":"/user/hand/right/input/trigger/value","value":1.0}
{"t":2.6,"path":"/user/hand/right/input/aim/pose","pose":{"p":[0.1123,0.46,-0.95],"q":[-0.70710678,0.02,0,0.70710678]}}
{"t":2.7,"path":"/user/hand/right/input/trigger/value","value":0.0}
{"t":3.4,"event":"exit"}
)");
  const auto commits = records(read_lines(recording), "commit");
  ASSERT_EQ(commits.size(), 2u);
  ASSERT_EQ(commits[0].at("method"), "asan");
  ASSERT_NE(commits[1].at("method"), "asan") << "the panel did not switch the method";

  const auto r = replay(recording, dir / "fixed", "--method asan --no-pictures");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("commit 1/2"), std::string::npos) << r.output;
  const std::size_t second = r.output.find("commit 2/2");
  ASSERT_NE(second, std::string::npos) << r.output;
  EXPECT_NE(r.output.find("match (d)", second), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("MISMATCH"), std::string::npos) << r.output;
  // The first commit, made with asan, is still held to its hash.
  EXPECT_NE(r.output.substr(0, second).find("  match  "), std::string::npos) << r.output;
  // With the second commit's method throughout, the first is solved otherwise, so the second starts from
  // another model than it did: compared by d too, not by a hash it cannot have.
  const auto other = replay(recording, dir / "other",
                            "--method " + commits[1].at("method").get<std::string>() + " --no-pictures");
  ASSERT_EQ(other.status, 0) << other.output;
  EXPECT_EQ(other.output.find("MISMATCH"), std::string::npos) << other.output;
  EXPECT_EQ(other.output.find("  match  "), std::string::npos) << other.output;
}

TEST(ReplayXr, CompareReplaysEachMethodAndPutsThemSideBySide) {
  const fs::path dir = test_dir();
  const auto r = replay(record_session(dir), dir / "cmp", "--compare asan,arap-sr --no-pictures");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* file : {"asan/commit-02.metrics.json", "arap-sr/commit-02.metrics.json", "compare.html"})
    EXPECT_TRUE(fs::exists(dir / "cmp" / file)) << file << "\n" << r.output;
  const std::string page = file_bytes(dir / "cmp" / "compare.html");
  EXPECT_NE(page.find("arap-sr/report.html"), std::string::npos);
  EXPECT_NE(page.find("<th>Push/pull 2</th>"), std::string::npos);
  EXPECT_NE(page.find("across d: "), std::string::npos);
  EXPECT_NE(page.find(" mm, max "), std::string::npos);
  EXPECT_NE(page.find("<b>"), std::string::npos);  // each row's best per criterion
  // The paper's point on the bonnet pulled forward: ASAN keeps the curvature signs, ARAP-s&r reverses many.
  const auto asan = nlohmann::json::parse(file_bytes(dir / "cmp" / "asan" / "commit-01.metrics.json"));
  const auto arap = nlohmann::json::parse(file_bytes(dir / "cmp" / "arap-sr" / "commit-01.metrics.json"));
  EXPECT_LT(double(asan.at("gaussian_sign_reversal_fraction")), 0.01);
  EXPECT_GT(double(arap.at("gaussian_sign_reversal_fraction")), 0.1);
}

TEST(ReplayXr, AChangedHashIsNamedAsTheFirstMismatch) {
  const fs::path dir = test_dir();
  const fs::path session = record_session(dir);
  auto lines = text_lines(session);
  size_t line = 0;
  for (size_t i = 0; i < lines.size(); ++i)
    if (lines[i].find("\"record\":\"commit\"") != std::string::npos) {
      auto j = nlohmann::json::parse(lines[i]);
      j["hash"] = "0x0123456789abcdef";
      lines[i] = j.dump();
      line = i + 1;
      break;
    }
  ASSERT_GT(line, 0u);
  write_lines(session, lines);
  const auto r = replay(session, dir / "out", "--no-pictures");
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("mismatch at commit 1 (recording line " + std::to_string(line) + ")"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("0x0123456789abcdef"), std::string::npos) << r.output;
}

TEST(ReplayXr, TruncatedRecordingReplaysUpToTheCut) {
  const fs::path dir = test_dir();
  const fs::path session = record_session(dir);
  // Cut in the middle of the line after the first commit record, as a crash while writing would.
  const std::string bytes = file_bytes(session);
  const size_t commit = bytes.find("\"record\":\"commit\"");
  ASSERT_NE(commit, std::string::npos);
  const size_t next_line = bytes.find('\n', commit) + 1;
  const size_t cut = next_line + 10;
  ASSERT_LT(cut, bytes.size());
  std::ofstream(session, std::ios::binary | std::ios::trunc) << bytes.substr(0, cut);
  const size_t cut_line = size_t(std::count(bytes.begin(), bytes.begin() + long(next_line), '\n')) + 1;

  const auto r = replay(session, dir / "out", "--no-pictures");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("line " + std::to_string(cut_line) + " is cut off"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("replayed up to the cut"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("commit 1/1"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "commit-01.off"));

  // Cut inside the header: nothing to replay, and it says so.
  std::ofstream(session, std::ios::binary | std::ios::trunc) << bytes.substr(0, 40);
  const auto header_cut = replay(session, dir / "out2", "--no-pictures");
  EXPECT_NE(header_cut.status, 0) << header_cut.output;
  EXPECT_NE(header_cut.output.find(session.string() + ":1: the header line is cut off"), std::string::npos)
      << header_cut.output;
}

TEST(ReplayXr, AnotherModelIsRefusedBySha256) {
  const fs::path dir = test_dir();
  const fs::path session = record_session(dir);
  // The same mesh with one more comment line: another file, another SHA-256.
  std::ofstream(dir / "other.off", std::ios::binary) << file_bytes(kHood) << "# edited\n";
  const auto r = replay(session, dir / "out", "--model " + (dir / "other.off").string());
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find((dir / "other.off").string() + ": SHA-256"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("refusing to replay"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out" / "final.off"));
}

// The recorded solver thresholds decide how cold solves start: a malformed one is refused, not guessed.
TEST(ReplayXr, AMalformedSolverThresholdIsRefused) {
  const fs::path dir = test_dir();
  const fs::path session = record_session(dir);
  auto lines = text_lines(session);
  ASSERT_FALSE(lines.empty());
  const std::string key = "\"coarse_start_min_free\":";
  const std::size_t at = lines[0].find(key);
  ASSERT_NE(at, std::string::npos) << lines[0];
  const std::size_t end = lines[0].find_first_of(",}", at + key.size());
  lines[0] = lines[0].substr(0, at + key.size()) + "\"many\"" + lines[0].substr(end);
  write_lines(session, lines);
  const auto r = replay(session, dir / "out", "--no-pictures");
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find(session.string() +
                          ": solver.coarse_start_min_free must be an integer >= -1, got \"many\""),
            std::string::npos)
      << r.output;
}

// A damaged header value is named as the recording's (not as an option the user never typed, nor as every
// push/pull failing in the replay).
TEST(ReplayXr, ADamagedHeaderValueIsNamedAsTheRecordings) {
  const fs::path dir = test_dir();
  const fs::path session = record_session(dir);
  const auto recorded = text_lines(session);
  ASSERT_FALSE(recorded.empty());
  // (from, to, what the message names)
  const std::tuple<std::string, std::string, std::string> cases[] = {
      {"\"method\":\"asan\"", "\"method\":\"bogus\"", "header option \"method\""},
      {"\"mu\":100.0", "\"mu\":0.5", "header option \"mu\""},
      // Wrong types and values the replay read unchecked: a raw JSON library error naming nothing, an error
      // blaming --up/--front the user never typed, "|d| inf mm" and NaN in the report.
      {"\"colour\":\"displacement\"", "\"colour\":5", "header option \"colour\""},
      {"\"format\":\"pushpull-session-", "\"format\":8,\"x\":\"", "the header's \"format\""},
      {"\"behaviour_format\":", "\"behaviour_format\":\"new\",\"x\":", "the header's \"behaviour_format\""},
      {"\"front\":[0.0,-1.0,0.0]", "\"front\":[0.0,0.0,2.0]",
       "header options \"up\" and \"front\" are parallel"},
      {"\"life_size_scale\":1.0", "\"life_size_scale\":1e308", "the header's \"life_size_scale\" 1e+308"}};
  for (const auto& [from, to, named] : cases) {
    SCOPED_TRACE(to);
    auto lines = recorded;
    ASSERT_NE(lines[0].find(from), std::string::npos) << from << " in " << lines[0];
    for (std::size_t at = lines[0].find(from); at != std::string::npos;
         at = lines[0].find(from, at + to.size()))
      lines[0].replace(at, from.size(), to);
    write_lines(session, lines);
    const auto r = replay(session, dir / "out", "--no-pictures");
    EXPECT_NE(r.status, 0) << r.output;
    EXPECT_NE(r.output.find(session.string() + ":1: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(named), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("json.exception"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("inf mm"), std::string::npos) << r.output;
  }
}

// What undo and redo left is compared too: the recording's end record holds the final model's hash and the
// commit count (a replay that lost an undo, or a damaged end record, passed "all checks").
TEST(ReplayXr, TheFinalModelIsComparedWithTheRecordedEnd) {
  const fs::path dir = test_dir();
  const fs::path session = record_session(dir);
  const auto recorded = text_lines(session);
  {  // The end record's hash damaged.
    auto lines = recorded;
    std::size_t line = 0;
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (lines[i].find("\"record\":\"end\"") != std::string::npos) {
        auto j = nlohmann::json::parse(lines[i]);
        j["hash"] = "0x0123456789abcdef";
        lines[i] = j.dump();
        line = i + 1;
      }
    ASSERT_GT(line, 0u);
    write_lines(session, lines);
    const auto r = replay(session, dir / "out", "--no-pictures");
    EXPECT_NE(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("mismatch at the session's end (recording line " + std::to_string(line) + ")"),
              std::string::npos)
        << r.output;
  }
  {  // The redo record gone: the replay undoes the second push/pull and ends on the first.
    auto lines = recorded;
    const auto before = lines.size();
    lines.erase(std::remove_if(
                    lines.begin(), lines.end(),
                    [](const std::string& l) { return l.find("\"record\":\"redo\"") != std::string::npos; }),
                lines.end());
    ASSERT_EQ(lines.size() + 1, before);
    write_lines(session, lines);
    const auto r = replay(session, dir / "out", "--no-pictures");
    EXPECT_NE(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("mismatch at the session's end"), std::string::npos) << r.output;
  }
}

// Without --method every push/pull is solved as its commit record says: a commit solved with another method
// (a damaged record, a lost method change) is a mismatch, not a "match (d)".
TEST(ReplayXr, ACommitSolvedWithAnotherMethodThanRecordedIsAMismatch) {
  const fs::path dir = test_dir();
  const fs::path session = record_session(dir);
  auto lines = text_lines(session);
  std::size_t line = 0;
  for (std::size_t i = 0; i < lines.size() && line == 0; ++i)
    if (lines[i].find("\"record\":\"commit\"") != std::string::npos) {
      auto j = nlohmann::json::parse(lines[i]);
      j["method"] = "arap-sr";
      lines[i] = j.dump();
      line = i + 1;
    }
  ASSERT_GT(line, 0u);
  write_lines(session, lines);
  const auto r = replay(session, dir / "out", "--no-pictures");
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("mismatch at commit 1 (recording line " + std::to_string(line) +
                          "): solved with asan, recorded with arap-sr"),
            std::string::npos)
      << r.output;
}

// One replay at a time in an output folder: two at once mixed their recordings and reports, and each said
// "all checks passed". A running replay holds a lock on the folder (flock on its descriptor); here the test
// holds it.
TEST(ReplayXr, AFolderAnotherReplayIsWritingIntoIsRefused) {
  const fs::path dir = test_dir();
  const fs::path session = record_session(dir);
  fs::create_directories(dir / "busy");
  std::ofstream(dir / "busy" / "notes.txt") << "the user's\n";
  const int fd = ::open((dir / "busy").c_str(), O_RDONLY | O_DIRECTORY);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  const auto held = replay(session, dir / "busy", "--no-pictures");
  EXPECT_NE(held.status, 0) << held.output;
  EXPECT_NE(
      held.output.find((dir / "busy").string() + ": another pushpull replay is writing into this folder"),
      std::string::npos)
      << held.output;
  EXPECT_FALSE(fs::exists(dir / "busy" / "replay-session.jsonl"));
  ::close(fd);  // released: the replay runs
  const auto free = replay(session, dir / "busy", "--no-pictures");
  EXPECT_EQ(free.status, 0) << free.output;
  EXPECT_TRUE(fs::exists(dir / "busy" / "notes.txt"));
}

TEST(ReplayXr, CorruptedLineIsNamedByItsNumber) {
  const fs::path dir = test_dir();
  const fs::path session = record_session(dir);
  auto lines = text_lines(session);
  ASSERT_GT(lines.size(), 20u);
  lines[11] = lines[11].substr(0, lines[11].size() / 2) + "]]";  // line 12
  write_lines(session, lines);
  const auto r = replay(session, dir / "out", "--no-pictures");
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find(session.string() + ":12: corrupted line"), std::string::npos) << r.output;
}

TEST(ReplayXr, AMalformedPressHeldRecordIsNamedByItsLine) {
  const fs::path dir = test_dir();
  const fs::path session = record_session(dir);
  auto lines = text_lines(session);
  ASSERT_GT(lines.size(), 20u);
  // A hold that ends before it begins.
  lines.insert(lines.begin() + 11, R"({"record":"press held","time":0.5,"from":0.9,"admitted":true})");  // line 12
  write_lines(session, lines);
  const auto r = replay(session, dir / "out", "--no-pictures");
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find(session.string() + ":12: corrupted line: a press held record needs"), std::string::npos)
      << r.output;
}

// A commit record's d (compared by a replay with another method) or method of the wrong type is named by its
// line, whichever method replays it: it used to pass the default replay and fail another method's with
// nlohmann's "cannot use at() with string", no file, no line, under "pushpull review".
TEST(ReplayXr, ACommitRecordWithAMalformedDOrMethodIsNamedByItsLine) {
  const fs::path dir = test_dir();
  const fs::path session = record_session(dir);
  const auto recorded = text_lines(session);
  std::size_t commit = 0;
  while (commit < recorded.size() && recorded[commit].find("\"record\":\"commit\"") == std::string::npos)
    ++commit;
  ASSERT_LT(commit, recorded.size());
  const std::pair<const char*, const char*> cases[] = {
      {"d", "\"north\""}, {"d", "[1, 2]"}, {"method", "7"}, {"method", "\"magic\""}};
  for (const auto& [key, value] : cases) {
    auto lines = recorded;
    nlohmann::json j = nlohmann::json::parse(lines[commit]);
    j[key] = nlohmann::json::parse(value);
    lines[commit] = j.dump();
    write_lines(session, lines);
    for (const char* method : {"", "--method arap-sr"}) {
      const auto r = replay(session, dir / "out", std::string("--no-pictures ") + method);
      EXPECT_NE(r.status, 0) << r.output;
      EXPECT_NE(r.output.find(session.string() + ":" + std::to_string(commit + 1) +
                              ": corrupted line: a commit record's \"" + key + "\""),
                std::string::npos)
          << key << " = " << value << " " << method << ": " << r.output;
    }
  }
}

// Input lines are in time order, a frame apart, and end with the session: a damaged time far ahead (which
// would step the replay's clock on without end, also in a recording cut short), one that goes back, or one
// past the end record is named by its line.
TEST(ReplayXr, AnInputTimeOutOfOrderOrPastTheEndIsNamedByItsLine) {
  const fs::path dir = test_dir();
  const fs::path session = record_session(dir);
  const auto recorded = text_lines(session);
  std::size_t last = 0;  // the last input line (before the end record)
  for (std::size_t k = 0; k < recorded.size(); ++k)
    if (recorded[k].find("\"t\":") != std::string::npos) last = k;
  ASSERT_GT(last, 20u);
  std::size_t middle = last / 2;
  while (middle > 0 && recorded[middle].find("\"t\":") == std::string::npos) --middle;
  ASSERT_GT(middle, 1u);
  auto with_time = [](std::string line, const std::string& t) {
    const std::size_t at = line.find("\"t\":");
    const std::size_t end = line.find_first_of(",}", at + 4);
    return line.substr(0, at + 4) + t + line.substr(end);
  };
  double end_time = 0.0;
  for (const std::string& l : recorded)
    if (l.find("\"record\":\"end\"") != std::string::npos)
      end_time = nlohmann::json::parse(l).at("time").get<double>();
  ASSERT_GT(end_time, 1.0);
  struct Case {
    std::size_t line;
    std::string t, says;
  };
  const Case cases[] = {{last, "1e12", "\"t\" 1e+12 s jumps"},
                        {middle, "1e12", "\"t\" 1e+12 s jumps"},
                        {middle, "0.0", "\"t\" 0 s is earlier than line"},
                        {last, std::to_string(end_time + 30.0), "is after the session's end"}};
  for (const Case& c : cases) {
    auto lines = recorded;
    lines[c.line] = with_time(lines[c.line], c.t);
    write_lines(session, lines);
    const auto r = replay(session, dir / "out", "--no-pictures");
    EXPECT_NE(r.status, 0) << r.output;
    EXPECT_NE(r.output.find(session.string() + ":" + std::to_string(c.line + 1) + ": corrupted line: "),
              std::string::npos)
        << c.t << ": " << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.t << ": " << r.output;
  }
  // The first input line far from the first frame, and a clock rate no review records (1e-9 Hz wrote 2 GB of
  // replay and never ended): named by their lines too.
  std::size_t first = 0;
  while (first < recorded.size() && recorded[first].find("\"t\":") == std::string::npos) ++first;
  std::size_t clock = 0;
  while (clock < recorded.size() && recorded[clock].find("\"record\":\"clock\"") == std::string::npos)
    ++clock;
  ASSERT_LT(clock, recorded.size());
  for (const auto& [line, text, says] :
       {std::tuple{first, with_time(recorded[first], "1e300"), std::string("on the first input line")},
        std::tuple{clock, std::string(R"({"record":"clock","time":0,"rate_hz":1e-9})"),
                   std::string("\"rate_hz\" must be a number from 10 to 1000")}}) {
    auto lines = recorded;
    lines[line] = text;
    write_lines(session, lines);
    const auto r = replay(session, dir / "out", "--no-pictures");
    EXPECT_NE(r.status, 0) << r.output;
    EXPECT_NE(r.output.find(session.string() + ":" + std::to_string(line + 1) + ": corrupted line: "),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << r.output;
  }
  // Cut short (no end record) with a damaged last time: still named, not replayed for ever.
  auto cut = recorded;
  cut[last] = with_time(cut[last], "1e12");
  cut.resize(last + 1);
  write_lines(session, cut);
  const auto r = replay(session, dir / "out", "--no-pictures");
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find(session.string() + ":" + std::to_string(last + 1) +
                          ": corrupted line: \"t\" 1e+12 s jumps"),
            std::string::npos)
      << r.output;
}

// The anchor record (the model moved in front of the reviewer's head) must be one, with finite numbers.
TEST(ReplayXr, AMalformedOrSecondAnchorRecordIsNamedByItsLine) {
  const fs::path dir = test_dir();
  const fs::path session = record_session(dir);
  const auto recorded = text_lines(session);
  ASSERT_GT(recorded.size(), 20u);
  ASSERT_EQ(
      std::count_if(recorded.begin(), recorded.end(),
                    [](const std::string& l) { return l.find(R"("record":"anchor")") != std::string::npos; }),
      1);
  for (const std::string& bad : {std::string(R"({"record":"anchor","time":0.1,"x":0,"z":0,"yaw":"left"})"),
                                 std::string(R"({"record":"anchor","time":0.1,"x":0,"z":0,"yaw":0})")}) {
    auto lines = recorded;
    const std::size_t at = lines.size() - 1;  // before the end record, after the recorded anchor
    lines.insert(lines.begin() + std::ptrdiff_t(at), bad);
    write_lines(session, lines);
    const auto r = replay(session, dir / "out", "--no-pictures");
    EXPECT_NE(r.status, 0) << r.output;
    EXPECT_NE(r.output.find(session.string() + ":" + std::to_string(at + 1) + ": corrupted line: a"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("anchor record"), std::string::npos) << r.output;
  }
}

// The bundled session (examples/sessions): the paper's three push/pulls on the bundled car replay with the
// recorded hashes (a change to the solver that moves them means recording it again: see its README).
// Another --method may fail a push/pull the recording committed (arap-s's energy goes negative under the
// bundled session's wheel-housing pull): the replay says so, pairs the other commits with theirs by release
// order and compares them by d, and the report lists what was not committed.
TEST(ReplayXr, APushPullAnotherMethodCannotCommitIsSaidAndTheRestCompared) {
  const fs::path dir = test_dir();
  const auto r = replay(fs::path(PUSHPULL_SOURCE_DIR) / "examples/sessions/paper_scenarios.jsonl",
                        dir / "out", "--method arap-s --no-pictures");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(
      r.output.find("release 3 of the recording (after commit 2) not committed (the model stays as it was): "
                    "deformer: arap-s: "
                    "the energy is "
                    "negative, -0.809092 (-0.453769 at the start)"),
      std::string::npos)
      << r.output;
  EXPECT_NE(
      r.output.find("2 commit(s) replayed of 3 recorded, 1 push/pull(s) not committed (recorded: 0); all "
                    "checks passed"),
      std::string::npos)
      << r.output;
  const std::string report = file_bytes(dir / "out" / "report.html");
  EXPECT_NE(report.find("<th>not committed</th>"), std::string::npos);
  EXPECT_NE(report.find("1 push/pull(s) the solver could not commit"), std::string::npos);
}

TEST(ReplayXr, BundledPaperSessionReplaysWithTheRecordedHashes) {
  const fs::path dir = test_dir();
  const auto r = replay(fs::path(PUSHPULL_SOURCE_DIR) / "examples/sessions/paper_scenarios.jsonl", dir / "out",
                        "--no-pictures");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("3 commit(s) replayed of 3 recorded; all checks passed"), std::string::npos) << r.output;
  for (const char* d : {"|d| 100.0 mm", "|d| 55.0 mm", "|d| 110.0 mm"})
    EXPECT_NE(r.output.find(d), std::string::npos) << d << "\n" << r.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "final.glb"));
  // Each commit's METRICS.json has what `pushpull deform` writes for the same pull: the energy after every
  // iteration, and the parts bound to the surface with how far each moved (windshield: 6 bound, 4 moved).
  std::ifstream in(dir / "out" / "commit-02.metrics.json");
  const nlohmann::json metrics = nlohmann::json::parse(in);
  EXPECT_EQ(metrics.at("energy_trace").size(), std::size_t(metrics.at("iterations").get<int>()));
  EXPECT_GT(metrics.at("initial_energy").get<double>(), 0.0);
  // The commit (a cold asan solve stopping within 80 iterations) checked its rate with the probe, and the
  // replay reports it as `pushpull deform` does.
  ASSERT_LE(metrics.at("iterations").get<int>(), 80);
  EXPECT_FALSE(metrics.at("probe_rate").is_null());
  EXPECT_GT(metrics.at("probe_evaluations").get<int>(), 1);
  EXPECT_FALSE(metrics.at("estimate_rate").is_null());
  EXPECT_FALSE(metrics.at("contraction_rate").is_null());
  EXPECT_GE(metrics.at("estimate_rate").get<double>(), metrics.at("contraction_rate").get<double>());
  const auto& parts = metrics.at("attached_parts").at("parts");
  EXPECT_EQ(parts.size(), 6u);
  EXPECT_EQ(std::count_if(parts.begin(), parts.end(),
                          [](const nlohmann::json& p) { return p.at("max_displacement") > 0.0; }),
            4);
}

}  // namespace
