// Building a render Primitive from decoded attribute arrays (accessors or Draco), with the checks
// every source needs: shapes, finite values, index ranges, strips and fans to triangle lists.
// Thread-safety: pure functions. Errors throw AssetError prefixed with `where`.
#pragma once

#include "draco_decode.hpp"
#include "pushpull/assets/scene.hpp"

#include <string>
#include <vector>

namespace pushpull::assets::detail {

// Stores `values` (#v by n) as the attribute `semantic`. Returns false (and does nothing) for
// semantics the render side does not keep (JOINTS_n, WEIGHTS_n, _CUSTOM...).
bool assign_attribute(Primitive& primitive, const std::string& semantic, FloatRows values,
                      const std::string& where);

// Converts `indices` of glTF `mode` (4 list, 5 strip, 6 fan) to a triangle list, checks every
// index against the vertex count and stores it. Missing indices (empty + !indexed): 0..#v-1.
void assign_triangles(Primitive& primitive, int mode, std::vector<std::uint32_t> indices, bool indexed,
                      const std::string& where);

// After all attributes: POSITION present, every attribute with #v rows, finite positions.
void check_primitive(const Primitive& primitive, const std::string& where);

}  // namespace pushpull::assets::detail
