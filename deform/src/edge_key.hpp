// Internal: a 64-bit key for an undirected edge (a, b), the same for (b, a). Vertex indices are >= 0.
#pragma once

#include <algorithm>
#include <cstdint>

namespace pushpull::deform::detail {

inline std::uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<std::uint32_t>(std::min(a, b));
  const auto hi = static_cast<std::uint32_t>(std::max(a, b));
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

}  // namespace pushpull::deform::detail
