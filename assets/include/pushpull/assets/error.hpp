// pushpull::assets::AssetError: a model file that cannot be read or written.
// The message names the file and the problem ("model.gltf: buffer 0: uri '../x.bin' points outside
// the model's folder"). Every refusal of untrusted input is reported this way, never by a crash.
#pragma once

#include <stdexcept>
#include <string>

namespace pushpull::assets {

struct AssetError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace pushpull::assets
