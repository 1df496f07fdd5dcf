// Outputs that would replace an input: `pushpull deform w.off --out w.off`, a --metrics named like the
// glTF's .bin, a --record over a --handle file. Writing them atomically still loses the input, so each
// command checks its outputs against every file it reads before it writes anything.
// Thread-safety: plain functions (they read the file system).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace pushpull::app {

// A file a command reads, and how to name it in a message ("the model", "the --handle file", "a file the
// model reads").
struct InputFile {
  std::filesystem::path path;
  std::string role;
};

// The model's files as the loader read them (assets::Model::source_files: the model file first, then the
// external buffers and images its URIs named), with their roles.
[[nodiscard]] std::vector<InputFile> model_inputs(const std::vector<std::filesystem::path>& source_files);

// Throws CommandError when `output` (given by `option`) names one of `inputs`: the same path after links, or
// the same name in the same folder reached by another path. Empty outputs, descriptors the process holds
// (/dev/stdout, ...) and hard links to an input (replacing one leaves the input as it was) pass.
void refuse_output_over_inputs(const std::string& option, const std::string& output,
                               const std::vector<InputFile>& inputs);

}  // namespace pushpull::app
