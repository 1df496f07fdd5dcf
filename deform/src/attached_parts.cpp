// AttachedParts: components near the region bound to the solved surface (see attached_parts.hpp).
#include "pushpull/deform/attached_parts.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "pushpull/deform/triangle_bvh.hpp"

namespace pushpull::deform {
namespace {

// Connected components over faces; vertices used by no face get their own component. Numbered in order of
// their lowest vertex.
std::vector<int> components(const Mesh& mesh) {
  const int nv = static_cast<int>(mesh.V.rows());
  std::vector<int> parent(static_cast<std::size_t>(nv));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v) {
      parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
      v = parent[static_cast<std::size_t>(v)];
    }
    return v;
  };
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    for (int c = 1; c < 3; ++c) {
      const int a = find(mesh.F(f, 0)), b = find(mesh.F(f, c));
      if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  }
  std::vector<int> label(static_cast<std::size_t>(nv), -1), id_of_root(static_cast<std::size_t>(nv), -1);
  int next = 0;
  for (int v = 0; v < nv; ++v) {
    const int root = find(v);
    if (id_of_root[static_cast<std::size_t>(root)] < 0) id_of_root[static_cast<std::size_t>(root)] = next++;
    label[static_cast<std::size_t>(v)] = id_of_root[static_cast<std::size_t>(root)];
  }
  return label;
}

// Orthonormal frame of triangle (a, b, c): columns edge direction, in-plane normal to it, face normal.
Eigen::Matrix3d face_frame(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = (b - a).normalized();
  const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
  Eigen::Matrix3d frame;
  frame << e1, n.cross(e1), n;
  return frame;
}

Eigen::Vector3d barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c) {
  const Eigen::Vector3d v0 = b - a, v1 = c - a, v2 = p - a;
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0), d21 = v2.dot(v1);
  const double denom = d00 * d11 - d01 * d01;
  const double v = (d11 * d20 - d01 * d21) / denom, w = (d00 * d21 - d01 * d20) / denom;
  return {1.0 - v - w, v, w};
}

}  // namespace

AttachedParts::AttachedParts(const Mesh& rest, const RegionOfInterest& roi, const AttachOptions& options)
    : F_(rest.F), rest_V_(rest.V) {
  const int nv = static_cast<int>(rest.V.rows());
  if (static_cast<int>(roi.role.size()) != nv) {
    throw std::invalid_argument("attached parts: the region has " + std::to_string(roi.role.size()) +
                                " roles for a mesh of " + std::to_string(nv) + " vertices");
  }
  auto in_region = [&](int v) { return roi.role[static_cast<std::size_t>(v)] != VertexRole::Outside; };
  const std::vector<int> label = components(rest);
  const int component_count = label.empty() ? 0 : *std::max_element(label.begin(), label.end()) + 1;
  std::vector<char> solved(static_cast<std::size_t>(component_count), 0);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int v = 0; v < nv; ++v) {
    if (!in_region(v)) continue;
    solved[static_cast<std::size_t>(label[static_cast<std::size_t>(v)])] = 1;
    lo = lo.cwiseMin(rest.V.row(v).transpose()), hi = hi.cwiseMax(rest.V.row(v).transpose());
  }
  if (!(hi.x() >= lo.x())) return;  // empty region
  reach_ = options.reach > 0.0 ? options.reach : 0.03 * (hi - lo).norm();

  // Region triangles (a corner in the region: they can move) and carrier triangles (all of the solved
  // components).
  std::vector<int> region_faces, carrier_faces;
  for (int f = 0; f < rest.F.rows(); ++f) {
    const int a = rest.F(f, 0);
    if (!solved[static_cast<std::size_t>(label[static_cast<std::size_t>(a)])]) continue;
    carrier_faces.push_back(f);
    if (in_region(rest.F(f, 0)) || in_region(rest.F(f, 1)) || in_region(rest.F(f, 2))) region_faces.push_back(f);
  }
  const TriangleBvh region_tree(rest.V, rest.F, region_faces);
  if (region_tree.empty()) return;

  // Candidate parts: components not solved with a vertex within reach of a region triangle.
  std::vector<double> gap(static_cast<std::size_t>(component_count), std::numeric_limits<double>::infinity());
  for (int v = 0; v < nv; ++v) {
    const int c = label[static_cast<std::size_t>(v)];
    if (solved[static_cast<std::size_t>(c)]) continue;
    const auto hit = region_tree.closest_point(rest.V, rest.V.row(v).transpose(),
                                               std::min(reach_, gap[static_cast<std::size_t>(c)]));
    if (hit) gap[static_cast<std::size_t>(c)] = std::min(gap[static_cast<std::size_t>(c)], hit->distance);
  }
  std::vector<int> part_index(static_cast<std::size_t>(component_count), -1);
  for (int c = 0; c < component_count; ++c) {
    if (gap[static_cast<std::size_t>(c)] <= reach_) {
      part_index[static_cast<std::size_t>(c)] = static_cast<int>(parts_.size());
      parts_.push_back({c, {}, gap[static_cast<std::size_t>(c)]});
    }
  }
  if (parts_.empty()) return;

  const TriangleBvh carrier_tree(rest.V, rest.F, carrier_faces);
  for (int v = 0; v < nv; ++v) {
    const int part = part_index[static_cast<std::size_t>(label[static_cast<std::size_t>(v)])];
    if (part < 0) continue;
    parts_[static_cast<std::size_t>(part)].vertices.push_back(v);
    const Eigen::Vector3d p = rest.V.row(v).transpose();
    const auto hit = carrier_tree.closest_point(rest.V, p);
    const int f = hit->face;
    const Eigen::Vector3d a = rest.V.row(rest.F(f, 0)), b = rest.V.row(rest.F(f, 1)), c = rest.V.row(rest.F(f, 2));
    bound_vertex_.push_back(v);
    carrier_face_.push_back(f);
    bary_.push_back(barycentric(hit->point, a, b, c));
    offset_.push_back(face_frame(a, b, c).transpose() * (p - hit->point));
  }
}

void AttachedParts::apply(Eigen::MatrixXd& V) const {
  if (V.rows() != rest_V_.rows() || V.cols() != 3) {
    throw std::invalid_argument("attached parts: positions must be " + std::to_string(rest_V_.rows()) +
                                " by 3");
  }
  for (std::size_t k = 0; k < bound_vertex_.size(); ++k) {
    const int f = carrier_face_[k];
    const int ia = F_(f, 0), ib = F_(f, 1), ic = F_(f, 2);
    if (V.row(ia) == rest_V_.row(ia) && V.row(ib) == rest_V_.row(ib) && V.row(ic) == rest_V_.row(ic)) continue;
    const Eigen::Vector3d a = V.row(ia), b = V.row(ib), c = V.row(ic);
    const Eigen::Vector3d q = bary_[k].x() * a + bary_[k].y() * b + bary_[k].z() * c;
    const double longest2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    const bool flat = !((b - a).cross(c - a).norm() > 1e-14 * longest2);  // collapsed: no frame, translate
    const Eigen::Vector3d ra = rest_V_.row(ia), rb = rest_V_.row(ib), rc = rest_V_.row(ic);
    const Eigen::Matrix3d frame = flat ? face_frame(ra, rb, rc) : face_frame(a, b, c);
    V.row(bound_vertex_[k]) = (q + frame * offset_[k]).transpose();
  }
}

}  // namespace pushpull::deform
