// Plane sections of a triangle mesh, chained into polylines.
#include "edge_key.hpp"
#include "pushpull/deform/metrics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace pushpull::deform {

using detail::edge_key;

namespace {

// The cut of V, and where V_carried (when given) puts the same surface points.
CarriedSection cut_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXd* V_carried, const Eigen::MatrixXi& F,
                        const Eigen::Vector3d& origin, const Eigen::Vector3d& normal) {
  const double length = normal.norm();
  if (!(length > 0.0) || !std::isfinite(length))
    throw std::invalid_argument("plane_section: zero or non-finite normal");
  if (V.cols() != 3 || F.cols() != 3)
    throw std::invalid_argument("plane_section: V and F must have 3 columns");
  if (F.size() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= V.rows())) {
    throw std::invalid_argument("plane_section: a face index is out of range");
  }
  const Eigen::Vector3d n = normal / length;
  const Eigen::VectorXd s = (V.rowwise() - origin.transpose()) * n;  // signed distances, #V

  // One crossing point per cut edge, shared by the faces on that edge; one segment per cut face.
  std::unordered_map<std::uint64_t, int> point_of_edge;
  std::vector<Eigen::Vector3d> points, carried_points;
  std::vector<std::vector<int>> segments_at;  // per point, the segments touching it
  std::vector<std::array<int, 2>> segments;
  auto crossing = [&](int a, int b) {
    const auto [it, inserted] = point_of_edge.try_emplace(edge_key(a, b), static_cast<int>(points.size()));
    if (inserted) {
      const double t = s(a) / (s(a) - s(b));
      points.push_back(V.row(a).transpose() + t * (V.row(b) - V.row(a)).transpose());
      if (V_carried != nullptr)
        carried_points.push_back(V_carried->row(a).transpose() +
                                 t * (V_carried->row(b) - V_carried->row(a)).transpose());
      segments_at.emplace_back();
    }
    return it->second;
  };
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    int ends[2];
    int found = 0;
    for (int c = 0; c < 3; ++c) {
      const int a = F(f, c);
      const int b = F(f, (c + 1) % 3);
      if ((s(a) >= 0.0) != (s(b) >= 0.0) && found < 2) ends[found++] = crossing(a, b);
    }
    if (found != 2 || ends[0] == ends[1]) continue;
    const int segment = static_cast<int>(segments.size());
    segments.push_back({ends[0], ends[1]});
    segments_at[static_cast<std::size_t>(ends[0])].push_back(segment);
    segments_at[static_cast<std::size_t>(ends[1])].push_back(segment);
  }

  std::vector<bool> used(segments.size(), false);
  CarriedSection out;
  auto walk = [&](int start) {
    SectionCurve curve, carried;
    std::vector<int> chain{start};
    int at = start;
    for (;;) {
      int next_segment = -1;
      for (const int segment : segments_at[static_cast<std::size_t>(at)]) {
        if (!used[static_cast<std::size_t>(segment)]) {
          next_segment = segment;
          break;
        }
      }
      if (next_segment < 0) break;
      used[static_cast<std::size_t>(next_segment)] = true;
      const auto& ends = segments[static_cast<std::size_t>(next_segment)];
      at = ends[0] == at ? ends[1] : ends[0];
      if (at == start) {
        curve.closed = carried.closed = true;
        break;
      }
      chain.push_back(at);
    }
    for (const int p : chain) {
      curve.points.push_back(points[static_cast<std::size_t>(p)]);
      if (V_carried != nullptr) carried.points.push_back(carried_points[static_cast<std::size_t>(p)]);
    }
    out.cut.push_back(std::move(curve));
    if (V_carried != nullptr) out.carried.push_back(std::move(carried));
  };
  // Open chains first, from their ends (points on a single segment), then the remaining loops.
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (segments_at[p].size() == 1 && !used[static_cast<std::size_t>(segments_at[p][0])])
      walk(static_cast<int>(p));
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    for (const int segment : segments_at[p]) {
      if (!used[static_cast<std::size_t>(segment)]) walk(static_cast<int>(p));
    }
  }
  return out;
}

}  // namespace

std::vector<SectionCurve> plane_section(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                        const Eigen::Vector3d& origin, const Eigen::Vector3d& normal) {
  return cut_mesh(V, nullptr, F, origin, normal).cut;
}

CarriedSection plane_section_carried(const Eigen::MatrixXd& V, const Eigen::MatrixXd& V_carried,
                                     const Eigen::MatrixXi& F, const Eigen::Vector3d& origin,
                                     const Eigen::Vector3d& normal) {
  if (V_carried.rows() != V.rows() || V_carried.cols() != V.cols())
    throw std::invalid_argument("plane_section_carried: V and V_carried differ in shape");
  return cut_mesh(V, &V_carried, F, origin, normal);
}

}  // namespace pushpull::deform
