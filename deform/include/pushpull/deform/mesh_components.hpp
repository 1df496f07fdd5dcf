// Connected components of a triangle mesh over its faces: the parts of a welded model (a body, a lamp, a
// trim) that a pull can deform together.
// Thread-safety: a plain function of its argument.
#pragma once

#include <vector>

#include "pushpull/deform/mesh.hpp"

namespace pushpull::deform {

// One label per vertex (#V): vertices joined by faces share it; a vertex used by no face gets one of its own.
// Labels are 0, 1, ... in the order of each component's lowest vertex. Face indices must be in range.
[[nodiscard]] std::vector<int> face_components(const Mesh& mesh);

}  // namespace pushpull::deform
