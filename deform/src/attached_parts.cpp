// AttachedParts: components near the region bound to the solved surface (see attached_parts.hpp).
#include "pushpull/deform/attached_parts.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "mesh_graph.hpp"
#include "pushpull/deform/mesh_components.hpp"
#include "pushpull/deform/triangle_bvh.hpp"

namespace pushpull::deform {
namespace {

// The rotation that best maps the rest patch onto the moved one (Kabsch: polar factor of the covariance of
// centred positions, det +1). A patch of a triangle's corners and their neighbours spans an area even when
// the triangle is a sliver, whose own normal would flip on a tiny move.
Eigen::Matrix3d patch_rotation(const Eigen::MatrixXd& rest, const Eigen::MatrixXd& moved, const int* begin,
                               const int* end) {
  Eigen::Vector3d c0 = Eigen::Vector3d::Zero(), c1 = Eigen::Vector3d::Zero();
  for (const int* v = begin; v != end; ++v) c0 += rest.row(*v).transpose(), c1 += moved.row(*v).transpose();
  const double n = static_cast<double>(end - begin);
  c0 /= n, c1 /= n;
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (const int* v = begin; v != end; ++v)
    H += (moved.row(*v).transpose() - c1) * (rest.row(*v).transpose() - c0).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  if ((U * svd.matrixV().transpose()).determinant() < 0.0) U.col(2) = -U.col(2);
  return U * svd.matrixV().transpose();
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
  const std::vector<int> label = face_components(rest);
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
    if (in_region(rest.F(f, 0)) || in_region(rest.F(f, 1)) || in_region(rest.F(f, 2)))
      region_faces.push_back(f);
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
  const detail::VertexGraph graph = detail::build_vertex_graph(nv, rest.F, carrier_faces);
  std::vector<int> slot_of_vertex(static_cast<std::size_t>(nv), -1);
  std::vector<long> near(parts_.size(), 0);  // vertices within reach of the carrier, per part
  std::vector<int> slot_vertex;              // the carrier vertex at the centre of each patch
  for (int v = 0; v < nv; ++v) {
    const int part = part_index[static_cast<std::size_t>(label[static_cast<std::size_t>(v)])];
    if (part < 0) continue;
    parts_[static_cast<std::size_t>(part)].vertices.push_back(v);
    const Eigen::Vector3d p = rest.V.row(v).transpose();
    const auto hit = carrier_tree.closest_point(rest.V, p);
    near[static_cast<std::size_t>(part)] += hit->distance <= reach_ ? 1 : 0;
    const int f = hit->face;
    const Eigen::Vector3d a = rest.V.row(rest.F(f, 0)), b = rest.V.row(rest.F(f, 1)),
                          c = rest.V.row(rest.F(f, 2));
    std::array<int, 3> slots{};
    for (int k = 0; k < 3; ++k) {
      int& slot = slot_of_vertex[static_cast<std::size_t>(rest.F(f, k))];
      if (slot < 0) {  // the corner's patch, built below once every offset bound to it is known
        slot = static_cast<int>(slot_vertex.size());
        slot_vertex.push_back(rest.F(f, k));
      }
      slots[static_cast<std::size_t>(k)] = slot;
    }
    bound_vertex_.push_back(v);
    bound_part_.push_back(part);
    carrier_face_.push_back(f);
    carrier_slot_.push_back(slots);
    bary_.push_back(barycentric(hit->point, a, b, c));
    offset_.push_back(p - hit->point);
  }
  // How a part rides (see the header): on the surface when nearly all of its vertices lie within reach of
  // the solved surface, else as a rigid whole when the surface under it moves coherently, unless it is
  // larger than the region (the body is no part of a windscreen).
  const double region_size = (hi - lo).norm();
  std::vector<int> kept_index(parts_.size(), -1);
  std::vector<AttachedPart> kept;
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    parts_[k].on_surface = static_cast<double>(near[k]) >=
                           kOnSurfaceShare * static_cast<double>(parts_[k].vertices.size());
    Eigen::Vector3d part_lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
                    part_hi = -part_lo;
    for (const int v : parts_[k].vertices) {
      part_lo = part_lo.cwiseMin(rest.V.row(v).transpose());
      part_hi = part_hi.cwiseMax(rest.V.row(v).transpose());
    }
    if (!parts_[k].on_surface && (part_hi - part_lo).norm() > region_size) continue;
    kept_index[k] = static_cast<int>(kept.size());
    kept.push_back(std::move(parts_[k]));
  }
  if (kept.size() != parts_.size()) {  // drop the bindings of the parts left out
    std::size_t out = 0;
    for (std::size_t b = 0; b < bound_vertex_.size(); ++b) {
      const int part = kept_index[static_cast<std::size_t>(bound_part_[b])];
      if (part < 0) continue;
      bound_vertex_[out] = bound_vertex_[b], bound_part_[out] = part, carrier_face_[out] = carrier_face_[b];
      carrier_slot_[out] = carrier_slot_[b], bary_[out] = bary_[b], offset_[out] = offset_[b];
      ++out;
    }
    bound_vertex_.resize(out), bound_part_.resize(out), carrier_face_.resize(out);
    carrier_slot_.resize(out), bary_.resize(out), offset_.resize(out);
  }
  parts_ = std::move(kept);
  build_patches(graph, slot_vertex);
}

void AttachedParts::build_patches(const detail::VertexGraph& graph, const std::vector<int>& slot_vertex) {
  // The largest offset each patch carries (of the vertices bound to a face around its centre); a slot no kept
  // binding uses gets empty patches.
  std::vector<double> carried(slot_vertex.size(), 0.0);
  std::vector<char> used(slot_vertex.size(), 0);
  for (std::size_t k = 0; k < bound_vertex_.size(); ++k)
    for (const int slot : carrier_slot_[k]) {
      carried[static_cast<std::size_t>(slot)] =
          std::max(carried[static_cast<std::size_t>(slot)], offset_[k].norm());
      used[static_cast<std::size_t>(slot)] = 1;
    }
  patch_start_.assign(1, 0), ring_start_.assign(1, 0);
  patch_index_.clear(), ring_index_.clear();
  std::vector<int> seen_at(static_cast<std::size_t>(rest_V_.rows()), -1);  // slot that last took the vertex
  std::vector<int> patch, ring, next_ring;
  for (std::size_t slot = 0; slot < slot_vertex.size(); ++slot) {
    patch.clear(), ring.clear();
    if (used[slot]) {
      const int centre = slot_vertex[slot];
      // Running sums of the patch's rest positions relative to its centre (no cancellation on models far
      // from the origin), for its in-plane spread as it grows.
      const Eigen::Vector3d origin = rest_V_.row(centre).transpose();
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      Eigen::Matrix3d sum_outer = Eigen::Matrix3d::Zero();
      auto take = [&](int v, std::vector<int>& into) {
        if (seen_at[static_cast<std::size_t>(v)] == static_cast<int>(slot)) return;
        seen_at[static_cast<std::size_t>(v)] = static_cast<int>(slot);
        patch.push_back(v);
        into.push_back(v);
        const Eigen::Vector3d p = rest_V_.row(v).transpose() - origin;
        sum += p, sum_outer += p * p.transpose();
      };
      take(centre, ring);
      for (int rings = 0; rings < kMaxPatchRings && !ring.empty(); ++rings) {
        next_ring.clear();
        for (const int v : ring)
          for (const int* w = graph.begin(v); w != graph.end(v); ++w) take(*w, next_ring);
        ring.swap(next_ring);
        // The centre and its neighbours: what decides whether the surface moved there.
        if (rings == 0) ring_index_.insert(ring_index_.end(), patch.begin(), patch.end());
        if (rings + 1 >= kMinPatchRings && (static_cast<int>(patch.size()) >= kMaxPatchVertices ||
                                            in_plane_spread(sum, sum_outer, patch.size()) >= carried[slot]))
          break;
      }
      // The rotation is as well defined by a few points spread over the patch as by all of them (its
      // conditioning is the spread's), and apply() fits one per patch for every snapshot: the centre and an
      // even sample of the rings in the order they were grown.
      if (patch.size() > static_cast<std::size_t>(kPatchPoints)) {
        const std::size_t others = patch.size() - 1, wanted = std::size_t(kPatchPoints) - 1;
        for (std::size_t k = 0; k < wanted; ++k) patch[1 + k] = patch[1 + k * others / wanted];
        patch.resize(std::size_t(kPatchPoints));
      }
      std::sort(patch.begin(), patch.end());
    }
    patch_index_.insert(patch_index_.end(), patch.begin(), patch.end());
    patch_start_.push_back(static_cast<int>(patch_index_.size()));
    ring_start_.push_back(static_cast<int>(ring_index_.size()));
  }
}

double AttachedParts::in_plane_spread(const Eigen::Vector3d& sum, const Eigen::Matrix3d& sum_outer,
                                      std::size_t count) {
  const double n = static_cast<double>(count);
  const Eigen::Vector3d mean = sum / n;
  const Eigen::Matrix3d C = sum_outer / n - mean * mean.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(C, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(eigen.eigenvalues()(1), 0.0));  // ascending: (1) is the middle one
}

void AttachedParts::apply(Eigen::MatrixXd& V) const {
  if (V.rows() != rest_V_.rows() || V.cols() != 3) {
    throw std::invalid_argument("attached parts: positions must be " + std::to_string(rest_V_.rows()) +
                                " by 3");
  }
  if (bound_vertex_.empty()) return;
  // One rotation per carrier vertex whose surroundings moved (identity for the others).
  const std::size_t slots = patch_start_.size() - 1;
  std::vector<Eigen::Matrix3d> rotation(slots, Eigen::Matrix3d::Identity());
  std::vector<char> moved(slots, 0);
  for (std::size_t slot = 0; slot < slots; ++slot) {
    // Moved: the centre or a neighbour of it (the patch grown for the rotation can reach into the region
    // from where the solve left the surface byte-identical, whose parts then stay exactly put).
    for (int k = ring_start_[slot]; k < ring_start_[slot + 1] && !moved[slot]; ++k) {
      const int v = ring_index_[static_cast<std::size_t>(k)];
      moved[slot] = V.row(v) != rest_V_.row(v);
    }
    if (moved[slot])
      rotation[slot] = patch_rotation(rest_V_, V, patch_index_.data() + patch_start_[slot],
                                      patch_index_.data() + patch_start_[slot + 1]);
  }
  // Where each bound vertex goes with the surface under it: the bound point moves with its triangle, the
  // offset turns with the corners' rotations blended by the barycentric coordinates (continuous from one
  // triangle to the next, so a part bends with the surface instead of stepping from triangle to triangle),
  // its length kept.
  std::vector<Eigen::Vector3d> follow(bound_vertex_.size());
  std::vector<char> part_moved(parts_.size(), 0);
  for (std::size_t k = 0; k < bound_vertex_.size(); ++k) {
    const std::array<int, 3>& slot = carrier_slot_[k];
    const Eigen::Vector3d rest_position = rest_V_.row(bound_vertex_[k]).transpose();
    if (!moved[static_cast<std::size_t>(slot[0])] && !moved[static_cast<std::size_t>(slot[1])] &&
        !moved[static_cast<std::size_t>(slot[2])]) {  // nothing under it moved
      follow[k] = rest_position;
      continue;
    }
    part_moved[static_cast<std::size_t>(bound_part_[k])] = 1;
    const int f = carrier_face_[k];
    const Eigen::Vector3d q = bary_[k].x() * V.row(F_(f, 0)).transpose() +
                              bary_[k].y() * V.row(F_(f, 1)).transpose() +
                              bary_[k].z() * V.row(F_(f, 2)).transpose();
    Eigen::Vector3d turned = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c)
      turned +=
          bary_[k](c) * (rotation[static_cast<std::size_t>(slot[static_cast<std::size_t>(c)])] * offset_[k]);
    const double length = turned.norm();
    // (The blend of rotations apart by angle a shortens the offset by about cos(a/2): put back.)
    follow[k] = q + (length > 0.5 * offset_[k].norm() ? turned * (offset_[k].norm() / length) : turned);
  }
  // Parts off the surface: the rigid motion that best fits where their vertices would go, when it fits.
  std::vector<Eigen::Matrix3d> part_rotation(parts_.size(), Eigen::Matrix3d::Identity());
  std::vector<Eigen::Vector3d> part_from(parts_.size(), Eigen::Vector3d::Zero()),
      part_to(parts_.size(), Eigen::Vector3d::Zero());
  std::vector<char> rigid_ok(parts_.size(), 0);
  {
    std::vector<long> count(parts_.size(), 0);
    for (std::size_t k = 0; k < bound_vertex_.size(); ++k) {
      const std::size_t part = static_cast<std::size_t>(bound_part_[k]);
      part_from[part] += rest_V_.row(bound_vertex_[k]).transpose();
      part_to[part] += follow[k];
      ++count[part];
    }
    std::vector<Eigen::Matrix3d> H(parts_.size(), Eigen::Matrix3d::Zero());
    for (std::size_t part = 0; part < parts_.size(); ++part) {
      if (count[part] > 0)
        part_from[part] /= static_cast<double>(count[part]),
            part_to[part] /= static_cast<double>(count[part]);
    }
    for (std::size_t k = 0; k < bound_vertex_.size(); ++k) {
      const std::size_t part = static_cast<std::size_t>(bound_part_[k]);
      H[part] += (follow[k] - part_to[part]) *
                 (rest_V_.row(bound_vertex_[k]).transpose() - part_from[part]).transpose();
    }
    std::vector<double> residual2(parts_.size(), 0.0), motion2(parts_.size(), 0.0);
    for (std::size_t part = 0; part < parts_.size(); ++part) {
      if (parts_[part].on_surface || !part_moved[part]) continue;
      const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H[part], Eigen::ComputeFullU | Eigen::ComputeFullV);
      Eigen::Matrix3d U = svd.matrixU();
      if ((U * svd.matrixV().transpose()).determinant() < 0.0) U.col(2) = -U.col(2);
      part_rotation[part] = U * svd.matrixV().transpose();
    }
    for (std::size_t k = 0; k < bound_vertex_.size(); ++k) {
      const std::size_t part = static_cast<std::size_t>(bound_part_[k]);
      if (parts_[part].on_surface || !part_moved[part]) continue;
      const Eigen::Vector3d p = rest_V_.row(bound_vertex_[k]).transpose();
      const Eigen::Vector3d rigid = part_to[part] + part_rotation[part] * (p - part_from[part]);
      residual2[part] += (rigid - follow[k]).squaredNorm();
      motion2[part] += (follow[k] - p).squaredNorm();
    }
    for (std::size_t part = 0; part < parts_.size(); ++part)
      rigid_ok[part] = residual2[part] <= kCoherentMotion * kCoherentMotion * motion2[part];
  }
  for (std::size_t k = 0; k < bound_vertex_.size(); ++k) {
    const std::size_t part = static_cast<std::size_t>(bound_part_[k]);
    if (!part_moved[part]) continue;  // exact values stay
    if (parts_[part].on_surface) {
      V.row(bound_vertex_[k]) = follow[k].transpose();
    } else if (rigid_ok[part]) {
      const Eigen::Vector3d p = rest_V_.row(bound_vertex_[k]).transpose();
      V.row(bound_vertex_[k]) = (part_to[part] + part_rotation[part] * (p - part_from[part])).transpose();
    }  // else: the surface under it does not move as one (a wheel under a pulled arch): it stays
  }
}

}  // namespace pushpull::deform
