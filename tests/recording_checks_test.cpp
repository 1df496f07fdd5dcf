// A damaged session recording is named by its file and line before anything is replayed: fields of the wrong
// type (they gave nlohmann's bare "type must be number, but is string"), an event xr/sim does not know (it
// was blamed on the OpenXR runtime), a zero up axis in the header, a first input far from the first frame and
// a clock rate no review records (both replayed without end), a folder given as the recording.
#include "command_runner.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using pushpull::testing::CommandResult;
using pushpull::testing::run_pushpull;

const fs::path kBundled = fs::path(PUSHPULL_SOURCE_DIR) / "examples" / "sessions" / "paper_scenarios.jsonl";

std::vector<std::string> lines_of(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The index of the first line `match` accepts (parsed as JSON).
std::size_t first_line(const std::vector<std::string>& lines, const std::function<bool(const json&)>& match) {
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const json j = json::parse(lines[k], nullptr, false);
    if (!j.is_discarded() && match(j)) return k;
  }
  ADD_FAILURE() << "no such line in " << kBundled;
  return 0;
}

class RecordingChecks : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pushpull_recording_checks_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    lines_ = lines_of(kBundled);
    ASSERT_GT(lines_.size(), 100u);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // Writes the bundled recording with line `index` edited by `edit`, replays it, and expects the refusal to
  // name that line and say `says`.
  void expect_named(std::size_t index, const std::function<void(json&)>& edit, const std::string& says) {
    std::vector<std::string> lines = lines_;
    json j = json::parse(lines[index]);
    edit(j);
    lines[index] = j.dump();
    const fs::path file = dir_ / "damaged.jsonl";
    std::ofstream(file) << [&] {
      std::ostringstream text;
      for (const std::string& line : lines) text << line << "\n";
      return text.str();
    }();
    const CommandResult r = run_pushpull("replay " + file.string() + " --out " + (dir_ / "out").string());
    EXPECT_NE(r.status, 0) << r.output;
    const std::string where = file.string() + ":" + std::to_string(index + 1) + ": corrupted line: ";
    EXPECT_NE(r.output.find(where + says), std::string::npos) << "expected: " << where << says << "\n"
                                                              << r.output;
  }
  fs::path dir_;
  std::vector<std::string> lines_;
};

TEST_F(RecordingChecks, DamagedLinesAreNamedByFileAndLine) {
  const auto is_record = [](const char* kind) {
    return [kind](const json& j) { return j.value("record", "") == kind; };
  };
  const std::size_t clock = first_line(lines_, is_record("clock"));
  expect_named(
      clock, [](json& j) { j["rate_hz"] = "30"; }, "a clock record's \"rate_hz\" must be a number");
  expect_named(
      clock, [](json& j) { j["rate_hz"] = 1e-9; }, "a clock record's \"rate_hz\" must be a number");
  expect_named(
      first_line(lines_, is_record("profile")), [](json& j) { j["profile"] = 5; },
      "a field has the wrong type");
  expect_named(
      first_line(lines_, is_record("release")), [](json& j) { j["time"] = "x"; },
      "a record's \"time\" is not a finite number");
  expect_named(
      0, [](json& j) { j["model_relative"] = 5; }, "the header's \"model_relative\" is not a path");
  expect_named(
      0, [](json& j) { j["life_size_scale"] = -1; },
      "the header's \"life_size_scale\" must be a finite number > 0, got -1");
  expect_named(
      0,
      [](json& j) {
        j["options"]["up"] = {0, 0, 0};
      },
      "header option \"up\" must be a finite, non-zero direction");
  expect_named(
      first_line(lines_, is_record("profile")), [&](json& j) { j = json::parse(lines_[0]); },
      "a second header");
  const std::size_t input = first_line(lines_, [](const json& j) { return j.contains("t"); });
  expect_named(
      input, [](json& j) { j["t"] = 1e300; }, "\"t\" 1e+300 s on the first input line");
  // A cancel record (Esc mid-drag in the desktop window) without its time.
  expect_named(
      first_line(lines_, is_record("profile")),
      [](json& j) {
        j = json{{"record", "cancel"}};
      },
      "a cancel record needs \"time\"");
}

// A commit or a committed release written twice (the replay then compared one commit with another's hash):
// the second copy is named.
TEST_F(RecordingChecks, ARepeatedCommitOrReleaseIsNamed) {
  for (const char* kind : {"commit", "release"}) {
    const std::size_t at = first_line(lines_, [&](const json& j) { return j.value("record", "") == kind; });
    std::vector<std::string> lines = lines_;
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(at) + 1, lines[at]);
    const fs::path file = dir_ / "twice.jsonl";
    {
      std::ofstream out(file);
      for (const std::string& line : lines) out << line << "\n";
    }
    const CommandResult r = run_pushpull("replay " + file.string() + " --out " + (dir_ / "out").string());
    EXPECT_NE(r.status, 0) << r.output;
    EXPECT_NE(r.output.find(file.string() + ":" + std::to_string(at + 2) + ": corrupted line: "),
              std::string::npos)
        << kind << ": " << r.output;
    EXPECT_NE(r.output.find(std::string(kind) == "commit" ? "a commit repeated or out of order"
                                                          : "(a release repeated)"),
              std::string::npos)
        << r.output;
  }
}

TEST_F(RecordingChecks, AnUnknownEventAndAFolderAreNamed) {
  std::vector<std::string> lines = lines_;
  lines.insert(lines.begin() + 250, R"({"t": 2.5, "event": "explode"})");
  const fs::path file = dir_ / "event.jsonl";
  {
    std::ofstream out(file);
    for (const std::string& line : lines) out << line << "\n";
  }
  const CommandResult r = run_pushpull("replay " + file.string() + " --out " + (dir_ / "out").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find(file.string() + ":251: corrupted line: unknown event \"explode\""),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("OpenXR"), std::string::npos) << r.output;
  const CommandResult folder = run_pushpull("replay " + dir_.string() + " --out " + (dir_ / "out").string());
  EXPECT_NE(folder.status, 0);
  EXPECT_NE(folder.output.find(dir_.string() + ": is a folder, not a session recording"), std::string::npos)
      << folder.output;
}

}  // namespace
