#include "atomic_file.hpp"

#include <stdexcept>
#include <string_view>

#include "pushpull/assets/error.hpp"
#include "pushpull/deform/mesh_io.hpp"

namespace pushpull::assets::detail {

// One implementation of the temp-file/fsync/rename protocol lives in deform's mesh I/O; assets reports its
// failures as AssetError ("FILE: problem") like every other asset problem.
void write_file_atomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  try {
    deform::write_file_atomically(
        path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  } catch (const std::runtime_error& e) {
    throw AssetError(e.what());
  }
}

}  // namespace pushpull::assets::detail
