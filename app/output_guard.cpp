#include "output_guard.hpp"

#include <system_error>

#include "commands.hpp"
#include "pushpull/deform/file_output.hpp"

namespace pushpull::app {

namespace fs = std::filesystem;

std::vector<InputFile> model_inputs(const std::vector<fs::path>& source_files) {
  std::vector<InputFile> inputs;
  for (std::size_t k = 0; k < source_files.size(); ++k)
    inputs.push_back({source_files[k], k == 0 ? "the model" : "a file the model reads"});
  return inputs;
}

void refuse_output_over_inputs(const std::string& option, const std::string& output,
                               const std::vector<InputFile>& inputs) {
  if (output.empty() || deform::holds_descriptor(output)) return;
  std::error_code error;
  const fs::path out_path = fs::absolute(output, error);
  for (const InputFile& input : inputs) {
    if (input.path.empty()) continue;
    // The same path after links, or the same entry of the same folder reached another way (a bind mount):
    // a temporary renamed over it replaces the input. (A hard link to the input is another entry: renaming
    // over it leaves the input's bytes as they were, so it is not refused.)
    const bool same =
        deform::same_output_file(output, input.path) ||
        (out_path.filename() == input.path.filename() &&
         fs::equivalent(out_path.parent_path(), fs::absolute(input.path, error).parent_path(), error) &&
         !error);
    if (same)
      throw CommandError(output + ": " + option + " names " + input.role + " (" + input.path.string() +
                         "): writing there would replace what this command reads; choose another name");
  }
}

}  // namespace pushpull::app
