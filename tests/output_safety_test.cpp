// Outputs never replace what a command reads (the model, a glTF's buffers and images, index files; a replay's
// recording and model in its --out), a review's --record never replaces an earlier recording, and a
// link to /dev/stdout is written through to the stream the shell opened instead of replacing the file at its
// end. Each refusal exits non-zero, names the output and what it would replace, and leaves the input as it
// was.
#include "command_runner.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace fs = std::filesystem;

namespace {

using pushpull::testing::CommandResult;
using pushpull::testing::run_command;
using pushpull::testing::run_pushpull;

const fs::path kHood = fs::path(PUSHPULL_SOURCE_DIR) / "examples" / "hood.off";
const fs::path kCarFolder = fs::path(PUSHPULL_SOURCE_DIR) / "examples" / "AsamVehicle";
const std::string kPull =
    " --handle-at 0 0.6 0.9 --handle-radius 0.2 --roi-radius 0.5 --displacement 0 0 0.1";

std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class OutputSafety : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pushpull_output_safety_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  [[nodiscard]] std::string path(const std::string& leaf) const { return (dir_ / leaf).string(); }
  // Runs `arguments`, expects a refusal naming `output` and "would replace", and `input` unchanged.
  void expect_refused(const std::string& arguments, const std::string& output, const fs::path& input,
                      const std::string& why = "would replace") {
    const std::string before = bytes_of(input);
    ASSERT_FALSE(before.empty()) << input;
    const CommandResult r = run_pushpull(arguments);
    EXPECT_NE(r.status, 0) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find(output + ": "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(why), std::string::npos) << r.output;
    EXPECT_EQ(bytes_of(input), before) << input << " changed by: " << arguments;
  }
  fs::path dir_;
};

TEST_F(OutputSafety, DeformRefusesOutputsThatWouldReplaceItsInputs) {
  const std::string model = path("w.off");
  fs::copy_file(kHood, model);
  expect_refused("deform " + model + kPull + " --out " + model + " --metrics " + path("m.json"), model,
                 model);
  expect_refused("deform " + model + kPull + " --out " + path("x.off") + " --metrics " + model, model, model);
  // Through a link to the model.
  fs::create_symlink(model, path("link.off"));
  expect_refused("deform " + model + kPull + " --out " + path("link.off") + " --metrics " + path("m.json"),
                 path("link.off"), model);
  // An index file.
  std::ofstream(path("handle.txt")) << "0\n1\n2\n";
  std::ofstream(path("fixed.txt")) << "4000\n4001\n";
  expect_refused("deform " + model + " --handle " + path("handle.txt") + " --fixed " + path("fixed.txt") +
                     " --displacement 0 0 0.05 --out " + path("x.off") + " --metrics " + path("handle.txt"),
                 path("handle.txt"), path("handle.txt"));
  // A glTF's external buffer, named the way the output's folder sees it.
  fs::create_directories(path("car"));
  for (const auto& entry : fs::directory_iterator(kCarFolder))
    fs::copy_file(entry.path(), dir_ / "car" / entry.path().filename());
  expect_refused("deform " + path("car/vehicle_example.gltf") +
                     " --handle-at 1.855 0.694 0 --handle-radius 0.05 --roi-radius 2 --displacement 0.1 0 0 "
                     "--out " +
                     path("car.glb") + " --metrics " + path("car/../car/vehicle_example.bin"),
                 path("car/../car/vehicle_example.bin"), path("car/vehicle_example.bin"));
  EXPECT_FALSE(fs::exists(path("x.off")));
  EXPECT_FALSE(fs::exists(path("m.json")));
  EXPECT_FALSE(fs::exists(path("car.glb")));
  // A hard link to the model is another name of its bytes: a result written over that name (a temporary
  // renamed over it) leaves the model as it was, so it is not refused.
  fs::create_hard_link(model, path("hard.off"));
  const std::string before = bytes_of(model);
  const CommandResult hard =
      run_pushpull("deform " + model + kPull + " --out " + path("hard.off") + " --metrics " + path("m.json"));
  EXPECT_EQ(hard.status, 0) << hard.output;
  EXPECT_EQ(bytes_of(model), before);
  EXPECT_NE(bytes_of(path("hard.off")), before);
}

TEST_F(OutputSafety, RenderAndReviewRefuseOutputsOverTheModelsFiles) {
  fs::create_directories(path("car"));
  for (const auto& entry : fs::directory_iterator(kCarFolder))
    fs::copy_file(entry.path(), dir_ / "car" / entry.path().filename());
  // The glTF's texture is a PNG a render could be asked to write.
  expect_refused("render " + path("car/vehicle_example.gltf") + " --out " + path("car/License_Plate.png"),
                 path("car/License_Plate.png"), path("car/License_Plate.png"));
  // A review refuses before any session starts (no runtime needed).
  const std::string model = path("w.off");
  fs::copy_file(kHood, model);
  expect_refused("review " + model + " --out " + model, model, model);
  // An existing file at --record (here the model itself) is not replaced: a recording is a session's only
  // copy.
  expect_refused("review " + model + " --record " + model, model, model, "--record: a file is already there");
}

// A replay clears and writes the files it names as it does (commit-01.glb, commit-01.metrics.json,
// commit-01-after.png, final.glb, report.html, eyes/frame_000113_left.png; input.jsonl and
// replay-session.jsonl): a recording or a file the model reads lying there under such a name is refused
// before anything is removed (a model renamed final.gltf was deleted, then "no such file"). The user's own
// files that merely start alike (a recording named commit-log.jsonl, commit-notes.txt, a sketch in eyes/) are
// left alone: they used to be removed without a word.
TEST_F(OutputSafety, AReplayRefusesAnOutFolderThatHoldsItsInputsUnderItsNames) {
  const fs::path bundled = fs::path(PUSHPULL_SOURCE_DIR) / "examples" / "sessions" / "paper_scenarios.jsonl";
  const std::string model = (kCarFolder / "vehicle_example.gltf").string();
  for (const char* name : {"input.jsonl", "replay-session.jsonl", "final.glb", "commit-02.metrics.json"}) {
    fs::copy_file(bundled, path(name), fs::copy_options::overwrite_existing);
    expect_refused(
        "replay " + path(name) + " --model " + model + " --out " + dir_.string() + " --no-pictures",
        path(name), path(name), "under a name the replay writes or clears");
    fs::remove(path(name));
  }
  // Replayed twice into a folder holding the user's files: they stay, byte for byte; the second replay says
  // what of the first's it removed.
  fs::create_directories(path("keep/eyes"));
  fs::copy_file(bundled, path("keep/commit-log.jsonl"));
  std::ofstream(path("keep/commit-notes.txt")) << "the supervisor's notes\n";
  std::ofstream(path("keep/final.gltf")) << "{}\n";
  std::ofstream(path("keep/eyes/sketch.png")) << "not a capture\n";
  const std::string bundled_bytes = bytes_of(bundled);
  for (int run = 0; run < 2; ++run) {
    const CommandResult r = run_pushpull("replay " + path("keep/commit-log.jsonl") + " --model " + model +
                                         " --out " + path("keep") + " --no-pictures");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(r.output.find("removed") != std::string::npos, run == 1) << r.output;
    EXPECT_EQ(bytes_of(path("keep/commit-log.jsonl")), bundled_bytes);
    EXPECT_EQ(bytes_of(path("keep/commit-notes.txt")), "the supervisor's notes\n");
    EXPECT_EQ(bytes_of(path("keep/final.gltf")), "{}\n");
    EXPECT_EQ(bytes_of(path("keep/eyes/sketch.png")), "not a capture\n");
    EXPECT_TRUE(fs::exists(path("keep/commit-01.glb")));
  }
  // The model's own buffer under a name the replay writes, in --out: refused too (it was deleted before the
  // model was read).
  fs::create_directories(path("car"));
  for (const auto& entry : fs::directory_iterator(kCarFolder))
    fs::copy_file(entry.path(), dir_ / "car" / entry.path().filename());
  fs::rename(path("car/vehicle_example.bin"), path("car/final.glb"));
  {
    std::ifstream in(path("car/vehicle_example.gltf"));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t at = text.find("vehicle_example.bin");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, std::string("vehicle_example.bin").size(), "final.glb");
    std::ofstream(path("car/model.gltf")) << text;
  }
  // (The recording names the model by its SHA-256: a copy made for the edited model.)
  const CommandResult sum = run_command("sha256sum " + path("car/model.gltf"));
  ASSERT_EQ(sum.status, 0) << sum.output;
  std::string recording = bundled_bytes;
  const std::size_t key = recording.find("\"model_sha256\":\"");
  ASSERT_NE(key, std::string::npos);
  recording.replace(key + 16, 64, sum.output.substr(0, 64));
  fs::create_directories(path("rec"));
  std::ofstream(path("rec/session.jsonl")) << recording;
  const std::string buffer_bytes = bytes_of(path("car/final.glb"));
  const CommandResult buffer =
      run_pushpull("replay " + path("rec/session.jsonl") + " --model " + path("car/model.gltf") + " --out " +
                   path("car") + " --no-pictures");
  EXPECT_NE(buffer.status, 0);
  EXPECT_NE(buffer.output.find(path("car/final.glb") + ": a file the model reads lies in --out"),
            std::string::npos)
      << buffer.output;
  EXPECT_EQ(bytes_of(path("car/final.glb")), buffer_bytes);
  const CommandResult empty = run_pushpull("replay " + bundled.string() + " --out ''");
  EXPECT_NE(empty.status, 0);
  EXPECT_NE(empty.output.find("--out: an empty folder name"), std::string::npos) << empty.output;
}

TEST_F(OutputSafety, ALinkToStdoutIsWrittenThroughAndTheLogKeepsItsLines) {
  fs::create_symlink("/dev/stdout", path("stdout.json"));
  std::ofstream(path("log.txt")) << "KEEP ME\n";
  const CommandResult r =
      run_command("(" + std::string(PUSHPULL_EXECUTABLE) + " deform " + kHood.string() + kPull + " --out " +
                  path("z.off") + " --metrics " + path("stdout.json") + " >> " + path("log.txt") + " 2> " +
                  path("err.txt") + ")");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string log = bytes_of(path("log.txt"));
  EXPECT_EQ(log.rfind("KEEP ME\n", 0), 0u) << log.substr(0, 200);
  EXPECT_NE(log.find("\"input\""), std::string::npos) << "the metrics went to the log through the link";
  // Only the metrics: the summary goes to stderr when an output is stdout (it followed the JSON, which no
  // longer parsed).
  EXPECT_TRUE(nlohmann::json::accept(log.substr(8))) << log.substr(log.size() > 300 ? log.size() - 300 : 0);
  EXPECT_NE(bytes_of(path("err.txt")).find("pushpull deform: "), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_symlink(path("stdout.json")));
  // A picture to stdout is the PNG's bytes alone.
  const CommandResult png =
      run_command("(" + std::string(PUSHPULL_EXECUTABLE) + " render " + kHood.string() +
                  " --size 32 32 --out /dev/stdout > " + path("p.png") + " 2> " + path("err.txt") + ")");
  ASSERT_EQ(png.status, 0) << png.output;
  const std::string bytes = bytes_of(path("p.png"));
  ASSERT_GT(bytes.size(), 12u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  EXPECT_EQ(bytes.substr(bytes.size() - 8, 4), "IEND") << "text after the PNG's end";
}

TEST_F(OutputSafety, AnEmptyOutputNameIsRefusedByItsOption) {
  const CommandResult r =
      run_pushpull("deform " + kHood.string() + kPull + " --out " + path("x.off") + " --metrics ''");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--metrics: an empty file name"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("x.off")));
}

}  // namespace
