// Integration-test helpers for runs of `pushpull review` / `pushpull replay` against the simulated OpenXR
// runtime (xr/sim) on lavapipe: the environment prefix that points the loader at the build's runtime
// manifest, a fresh scratch folder per test, and the bundled bonnet and how it is placed on the stage.
// Needs PUSHPULL_XR_SIM_MANIFEST and PUSHPULL_SOURCE_DIR defined by the build. Thread-safety: none needed.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace pushpull::testing {

// "env XR_RUNTIME_JSON=<manifest> [VK_ICD_FILENAMES=<lavapipe>]", to put before a command line.
inline std::string xr_sim_environment() {
  std::string env = "env XR_RUNTIME_JSON=" + std::string(PUSHPULL_XR_SIM_MANIFEST);
  const char* lavapipe = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";
  if (std::filesystem::exists(lavapipe)) env += std::string(" VK_ICD_FILENAMES=") + lavapipe;
  return env;
}

// An empty folder <temp>/<suite>/<current test name>.
inline std::filesystem::path fresh_test_dir(const std::string& suite) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / suite / info->name();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// hood.off is Z-up with its front edge at y = 0 facing -Y: stood on the stage floor with the front edge
// towards the reviewer, 0.6 m away, it spans stage z -0.6 .. -1.8 and stage y 0 .. 0.11.
inline const std::string kHood = std::string(PUSHPULL_SOURCE_DIR) + "/examples/hood.off";
inline const std::string kHoodPlacement =
    " --up 0 0 1 --front 0 -1 0 --handle-radius 0.25 --roi-radius 0.9 --samples 1";

}  // namespace pushpull::testing
