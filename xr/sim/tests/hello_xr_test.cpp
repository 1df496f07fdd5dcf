// Debian's hello_xr (OpenXR-SDK-Source's sample app) against the simulated runtime, headless on
// lavapipe, under the OpenXR core validation layer: it renders, the compositor captures both eyes,
// and a scripted menu press makes it request exit (its "quit" action) and end with status 0.
#include "sim_fixture.hpp"

#include <gtest/gtest.h>

#include <stb/stb_image.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

using namespace sim_test;

namespace {

constexpr const char* kScript =
    R"({"t": 0.0, "path": "/user/hand/right/input/aim/pose", "pose": {"p": [0.15, 1.35, -0.5], "q": [0, 0, 0, 1]}}
{"t": 0.5, "event": "capture"}
{"t": 1.0, "path": "/user/hand/left/input/menu/click", "value": true}
{"t": 1.2, "path": "/user/hand/left/input/menu/click", "value": false}
)";

struct RunResult {
  int status = -1;
  bool timed_out = false;
  std::string output;
};

// Runs hello_xr with stdin on a pipe kept open (it quits at the first byte or EOF on stdin).
RunResult run_hello_xr(const char* graphics, const std::string& log_file, std::chrono::seconds timeout) {
  int in[2];
  if (pipe(in) != 0) return {};
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(in[0], STDIN_FILENO);
    close(in[1]);
    const int out = open(log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(out, STDOUT_FILENO);
    dup2(out, STDERR_FILENO);
    execl(PUSHPULL_HELLO_XR, PUSHPULL_HELLO_XR, "-g", graphics, static_cast<char*>(nullptr));
    _exit(127);
  }
  close(in[0]);
  RunResult r;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  int status = 0;
  for (;;) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (std::chrono::steady_clock::now() > deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      r.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  close(in[1]);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream log(log_file);
  std::stringstream ss;
  ss << log.rdbuf();
  r.output = ss.str();
  return r;
}

std::string tail(const std::string& s, std::size_t n = 4000) {
  return s.size() > n ? s.substr(s.size() - n) : s;
}

// Lines where a validation layer (OpenXR core validation, Vulkan's when hello_xr enables it) or
// hello_xr itself reports a problem. hello_xr's own note that Vulkan validation layers are not
// installed is not one.
std::string problems(const std::string& output) {
  std::istringstream in(output);
  std::string line, found;
  while (std::getline(in, line)) {
    if (line.find("No validation layers found") != std::string::npos) continue;
    for (const char* bad : {"VUID", "Error", "ERROR", "Warning", "WARNING"})
      if (line.find(bad) != std::string::npos) {
        found += line + "\n";
        break;
      }
  }
  return found;
}

TEST(HelloXrTest, RendersCubesAndExitsOnAScriptedMenuPress) {
  use_simulated_runtime();
  const std::string dir = temp_dir("run");
  const std::string capture = dir + "/capture";
  setenv("PUSHPULL_XR_SIM_INPUT", write_temp_file("quit.jsonl", kScript).c_str(), 1);
  setenv("PUSHPULL_XR_SIM_CAPTURE", capture.c_str(), 1);
  setenv("PUSHPULL_XR_SIM_WIDTH", "320", 1);
  setenv("PUSHPULL_XR_SIM_HEIGHT", "360", 1);
  setenv("XR_ENABLE_API_LAYERS", "XR_APILAYER_LUNARG_core_validation", 1);
  const RunResult r = run_hello_xr("Vulkan2", dir + "/hello_xr.log", std::chrono::seconds(120));
  ASSERT_FALSE(r.timed_out) << tail(r.output);
  EXPECT_EQ(r.status, 0) << tail(r.output);
  EXPECT_NE(r.output.find("XR_SESSION_STATE_FOCUSED"), std::string::npos) << tail(r.output);
  EXPECT_NE(r.output.find("XR_SESSION_STATE_STOPPING->XR_SESSION_STATE_IDLE"), std::string::npos);
  EXPECT_NE(r.output.find("->XR_SESSION_STATE_EXITING"), std::string::npos) << tail(r.output);
  EXPECT_NE(r.output.find("Core Validation"), std::string::npos) << "the core validation layer did not load";
  EXPECT_EQ(problems(r.output), "");

  // The capture event at t = 0.5 s: both eyes, with hello_xr's coloured cubes on its grey background.
  std::vector<std::string> images;
  for (const auto& e : std::filesystem::directory_iterator(capture)) images.push_back(e.path().string());
  ASSERT_EQ(images.size(), 2u);
  for (const std::string& file : images) {
    int w = 0, h = 0, c = 0;
    unsigned char* px = stbi_load(file.c_str(), &w, &h, &c, 3);
    ASSERT_NE(px, nullptr) << file;
    EXPECT_EQ(w, 320);
    EXPECT_EQ(h, 360);
    std::map<uint32_t, int> histogram;
    int cube = 0;
    for (int i = 0; i < w * h; ++i) {
      const int R = px[3 * i], G = px[3 * i + 1], B = px[3 * i + 2];
      histogram[(R << 16) | (G << 8) | B]++;
      // Cube faces are saturated red, green or blue (dark or bright); the background is grey.
      const int hi = std::max({R, G, B}), lo = std::min({R, G, B});
      if (hi > 40 && lo * 3 < hi) ++cube;
    }
    stbi_image_free(px);
    int background = 0;
    for (const auto& [colour, count] : histogram) background = std::max(background, count);
    EXPECT_LT(background, w * h * 97 / 100) << file << ": almost all one colour";
    EXPECT_GT(cube, 500) << file << ": no cube-coloured pixels";
  }
}

// The same app through XR_KHR_vulkan_enable (the application creates its VkInstance and VkDevice).
TEST(HelloXrTest, VulkanEnable1AlsoRunsAndExits) {
  use_simulated_runtime();
  const std::string dir = temp_dir("run");
  setenv("PUSHPULL_XR_SIM_INPUT", write_temp_file("quit.jsonl", kScript).c_str(), 1);
  setenv("PUSHPULL_XR_SIM_WIDTH", "320", 1);
  setenv("PUSHPULL_XR_SIM_HEIGHT", "360", 1);
  setenv("XR_ENABLE_API_LAYERS", "XR_APILAYER_LUNARG_core_validation", 1);
  const RunResult r = run_hello_xr("Vulkan", dir + "/hello_xr.log", std::chrono::seconds(120));
  ASSERT_FALSE(r.timed_out) << tail(r.output);
  EXPECT_EQ(r.status, 0) << tail(r.output);
  EXPECT_NE(r.output.find("->XR_SESSION_STATE_EXITING"), std::string::npos) << tail(r.output);
  EXPECT_EQ(problems(r.output), "");
}

}  // namespace
