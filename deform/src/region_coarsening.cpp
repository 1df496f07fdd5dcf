#include "region_coarsening.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

namespace pushpull::deform::detail {
namespace {

// 1 for an equilateral triangle, 0 for a degenerate one: 4 sqrt(3) area / sum of squared edge lengths.
double triangle_quality(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double squares = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  if (!(squares > 0.0)) return 0.0;
  return 2.0 * std::sqrt(3.0) * (b - a).cross(c - a).norm() / squares;
}

// A handed-over triangle may not turn by more than this (cosine of 60 degrees) ...
constexpr double kMinNormalCosine = 0.5;
// ... nor end thinner than half the thinnest triangle it replaces, unless it is at least this good; and
// never thinner than kMinQuality (halving from slivers round after round would otherwise reach triangles the
// solver drops as degenerate).
constexpr double kGoodQuality = 0.3;
constexpr double kMinQuality = 1e-3;

class Collapser {
 public:
  Collapser(const Eigen::Matrix3Xd& positions, const Eigen::MatrixX3i& faces, int n_free)
      : p_(positions),
        n_free_(n_free),
        incident_(static_cast<std::size_t>(positions.cols())),
        removed_(static_cast<std::size_t>(positions.cols()), 0),
        parent_(static_cast<std::size_t>(positions.cols()), -1),
        stamp_(static_cast<std::size_t>(positions.cols()), 0) {
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      const std::array<int, 3> t{faces(f, 0), faces(f, 1), faces(f, 2)};
      if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) continue;
      const int id = static_cast<int>(tris_.size());
      tris_.push_back(t);
      alive_.push_back(1);
      for (int v : t) incident_[static_cast<std::size_t>(v)].push_back(id);
    }
    // Collapses keep a closed fan closed (and an open one open), so this is decided once.
    interior_.assign(static_cast<std::size_t>(n_free), 0);
    for (int u = 0; u < n_free; ++u) interior_[static_cast<std::size_t>(u)] = closed_fan(u) ? 1 : 0;
  }

  // In rounds: each round visits the free interior vertices in order and collapses each one not next to a
  // collapse of this round into its nearest neighbour that allows it (a maximal independent set of
  // collapses, so each round thins the region evenly, by about a third). (Shortest edge first over the whole
  // region, with a heap or in sorted passes, gave the same coarse solve at 2-4x the time: 20 ms at 10K
  // vertices, 230 at 100K, against 9 and 121; timed by a scratch driver, not in the tree.)
  int run(int target_free) {
    int free_left = n_free_;
    std::vector<char> locked(static_cast<std::size_t>(p_.cols()), 0);
    std::vector<std::pair<double, int>> nearest;
    for (bool progress = true; progress && free_left > target_free;) {
      progress = false;
      std::fill(locked.begin(), locked.end(), 0);
      for (int u = 0; u < n_free_ && free_left > target_free; ++u) {
        if (removed_[static_cast<std::size_t>(u)] || !interior_[static_cast<std::size_t>(u)] ||
            locked[static_cast<std::size_t>(u)])
          continue;
        nearest.clear();
        for (int t : incident_[static_cast<std::size_t>(u)]) {  // each neighbour once: the fan is closed
          const int v = opposite(t, u).first;
          nearest.emplace_back((p_.col(u) - p_.col(v)).squaredNorm(), v);
        }
        std::sort(nearest.begin(), nearest.end());
        for (const auto& [length, v] : nearest) {
          if (!collapse(u, v)) continue;
          --free_left;
          progress = true;
          locked[static_cast<std::size_t>(v)] = 1;
          for (int t : incident_[static_cast<std::size_t>(v)]) {
            const auto [a, b] = opposite(t, v);
            locked[static_cast<std::size_t>(a)] = locked[static_cast<std::size_t>(b)] = 1;
          }
          break;
        }
      }
    }
    return free_left;
  }

  CoarseRegion result() const {
    CoarseRegion coarse;
    const int n = static_cast<int>(p_.cols());
    std::vector<int> coarse_index(static_cast<std::size_t>(n), -1);
    for (int v = 0; v < n; ++v) {
      if (removed_[static_cast<std::size_t>(v)]) continue;
      coarse_index[static_cast<std::size_t>(v)] = static_cast<int>(coarse.kept.size());
      coarse.kept.push_back(v);
      if (v < n_free_) ++coarse.kept_free;
    }
    coarse.ancestor.assign(static_cast<std::size_t>(n), -1);
    for (int v = 0; v < n; ++v) {
      int a = v;
      while (removed_[static_cast<std::size_t>(a)]) a = parent_[static_cast<std::size_t>(a)];
      coarse.ancestor[static_cast<std::size_t>(v)] = coarse_index[static_cast<std::size_t>(a)];
    }
    Eigen::Index count = 0;
    for (char alive : alive_) count += alive ? 1 : 0;
    coarse.faces.resize(count, 3);
    Eigen::Index f = 0;
    for (std::size_t t = 0; t < tris_.size(); ++t) {
      if (!alive_[t]) continue;
      for (int k = 0; k < 3; ++k)
        coarse.faces(f, k) = coarse_index[static_cast<std::size_t>(tris_[t][static_cast<std::size_t>(k)])];
      ++f;
    }
    return coarse;
  }

 private:
  // The triangle t seen from its vertex v: the other two in orientation order.
  std::pair<int, int> opposite(int t, int v) const {
    const std::array<int, 3>& tri = tris_[static_cast<std::size_t>(t)];
    const int k = tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
    return {tri[static_cast<std::size_t>((k + 1) % 3)], tri[static_cast<std::size_t>((k + 2) % 3)]};
  }

  // u's triangles form one closed, consistently oriented fan.
  bool closed_fan(int u) const {
    const std::vector<int>& tris = incident_[static_cast<std::size_t>(u)];
    if (tris.size() < 3) return false;
    std::vector<std::pair<int, int>> next;  // a -> b for each triangle (u, a, b)
    next.reserve(tris.size());
    for (int t : tris) next.push_back(opposite(t, u));
    std::sort(next.begin(), next.end());
    for (std::size_t k = 1; k < next.size(); ++k)
      if (next[k].first == next[k - 1].first) return false;  // an edge used twice the same way
    int at = next.front().first;
    for (std::size_t steps = 0; steps < next.size(); ++steps) {
      const auto it = std::lower_bound(next.begin(), next.end(), std::make_pair(at, -1));
      if (it == next.end() || it->first != at) return false;  // the fan is open
      at = it->second;
      if (at == next.front().first) return steps + 1 == next.size();  // one cycle through every triangle
    }
    return false;
  }

  void drop(int v, int t) {
    std::vector<int>& list = incident_[static_cast<std::size_t>(v)];
    list.erase(std::find(list.begin(), list.end(), t));
  }

  bool collapse(int u, int v) {
    if (!interior_[static_cast<std::size_t>(u)]) return false;
    const std::vector<int>& around_u = incident_[static_cast<std::size_t>(u)];
    // The two triangles with both u and v (a closed fan has exactly two for each neighbour, none if v is no
    // longer one) and the vertices opposite the edge in them.
    int shared[2] = {-1, -1}, across[2] = {-1, -1}, found = 0;
    for (int t : around_u) {
      const auto [a, b] = opposite(t, u);
      if (a != v && b != v) continue;
      if (found == 2) return false;
      shared[found] = t;
      across[found++] = a == v ? b : a;
    }
    if (found != 2) return false;
    // Link condition: the neighbours u and v share are exactly the two opposite the edge.
    ++current_stamp_;
    for (int t : around_u) {
      const auto [a, b] = opposite(t, u);
      stamp_[static_cast<std::size_t>(a)] = current_stamp_;
      stamp_[static_cast<std::size_t>(b)] = current_stamp_;
    }
    for (int t : incident_[static_cast<std::size_t>(v)]) {
      const auto [a, b] = opposite(t, v);
      for (int w : {a, b})
        if (w != u && w != across[0] && w != across[1] &&
            stamp_[static_cast<std::size_t>(w)] == current_stamp_)
          return false;
    }
    // Shape: no handed-over triangle turns over or ends much thinner than those it replaces.
    double worst_before = 1.0;
    for (int t : around_u) {
      const std::array<int, 3>& tri = tris_[static_cast<std::size_t>(t)];
      worst_before = std::min(worst_before, triangle_quality(p_.col(tri[0]), p_.col(tri[1]), p_.col(tri[2])));
    }
    const double needed = std::max(kMinQuality, std::min(kGoodQuality, 0.5 * worst_before));
    for (int t : around_u) {
      if (t == shared[0] || t == shared[1]) continue;
      const auto [a, b] = opposite(t, u);
      // v may not have a triangle on a and b already (a valence-3 u on a closed tetrahedron would leave two
      // coincident triangles).
      for (int w : incident_[static_cast<std::size_t>(v)]) {
        const auto [c, e] = opposite(w, v);
        if ((c == a && e == b) || (c == b && e == a)) return false;
      }
      const Eigen::Vector3d before = (p_.col(a) - p_.col(u)).cross(p_.col(b) - p_.col(u));
      const Eigen::Vector3d after = (p_.col(a) - p_.col(v)).cross(p_.col(b) - p_.col(v));
      if (!(before.dot(after) > kMinNormalCosine * before.norm() * after.norm())) return false;
      if (triangle_quality(p_.col(v), p_.col(a), p_.col(b)) < needed) return false;
    }
    for (int k = 0; k < 2; ++k) {
      alive_[static_cast<std::size_t>(shared[k])] = 0;
      drop(v, shared[k]);
      drop(across[k], shared[k]);
    }
    for (int t : around_u) {
      if (t == shared[0] || t == shared[1]) continue;
      for (int& w : tris_[static_cast<std::size_t>(t)])
        if (w == u) w = v;
      incident_[static_cast<std::size_t>(v)].push_back(t);
    }
    incident_[static_cast<std::size_t>(u)].clear();
    removed_[static_cast<std::size_t>(u)] = 1;
    parent_[static_cast<std::size_t>(u)] = v;
    return true;
  }

  const Eigen::Matrix3Xd& p_;
  int n_free_;
  std::vector<std::array<int, 3>> tris_;
  std::vector<char> alive_;
  std::vector<std::vector<int>> incident_;  // the live triangles at each vertex
  std::vector<char> removed_, interior_;
  std::vector<int> parent_;
  std::vector<unsigned> stamp_;  // the link condition's marks
  unsigned current_stamp_ = 0;
};

}  // namespace

CoarseRegion coarsen_region(const Eigen::Matrix3Xd& positions, const Eigen::MatrixX3i& faces, int n_free,
                            int target_free) {
  Collapser collapser(positions, faces, n_free);
  (void)collapser.run(std::max(target_free, 0));
  return collapser.result();
}

}  // namespace pushpull::deform::detail
