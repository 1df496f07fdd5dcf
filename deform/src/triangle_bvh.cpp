// TriangleBvh: median-split AABB tree, nearest-first closest-point and ray queries (see triangle_bvh.hpp).
#include "pushpull/deform/triangle_bvh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace pushpull::deform {
namespace {

constexpr int kLeafSize = 4;

Eigen::Vector3d corner(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int f, int c) {
  return V.row(F(f, c)).transpose();
}

// Squared distance from p to the box [lo, hi] (0 inside).
double box_distance2(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const Eigen::Vector3d d = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
  return d.squaredNorm();
}

// Ray-box slab test: the entry parameter, or +inf when missed within [0, max_t].
double box_entry(const Eigen::Vector3d& origin, const Eigen::Vector3d& inverse, const Eigen::Vector3d& lo,
                 const Eigen::Vector3d& hi, double max_t) {
  double t0 = 0.0, t1 = max_t;
  for (int k = 0; k < 3; ++k) {
    double a = (lo[k] - origin[k]) * inverse[k], b = (hi[k] - origin[k]) * inverse[k];
    if (std::isnan(a) || std::isnan(b)) {  // direction 0 on this axis and origin on a slab plane
      if (origin[k] < lo[k] || origin[k] > hi[k]) return std::numeric_limits<double>::infinity();
      continue;
    }
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return std::numeric_limits<double>::infinity();
  }
  return t0;
}

}  // namespace

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  // Ericson, Real-Time Collision Detection, 5.1.5: Voronoi regions of the vertices, edges and face.
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

TriangleBvh::TriangleBvh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<int>& faces)
    : F_(F) {
  auto keep = [&](int f) {
    const Eigen::Vector3d a = corner(V, F, f, 0), b = corner(V, F, f, 1), c = corner(V, F, f, 2);
    const double longest2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    return (b - a).cross(c - a).norm() > 1e-14 * longest2;
  };
  if (faces.empty()) {
    for (int f = 0; f < F.rows(); ++f)
      if (keep(f)) faces_.push_back(f);
  } else {
    for (int f : faces)
      if (keep(f)) faces_.push_back(f);
  }
  if (faces_.empty()) return;
  nodes_.reserve(2 * faces_.size() / kLeafSize + 2);
  nodes_.push_back({});
  build(0, 0, static_cast<int>(faces_.size()), V);
}

void TriangleBvh::build(int node, int begin, int end, const Eigen::MatrixXd& V) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  Eigen::Vector3d clo = lo, chi = hi;  // centroid bounds
  for (int k = begin; k < end; ++k) {
    const int f = faces_[static_cast<std::size_t>(k)];
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d p = corner(V, F_, f, c);
      lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
      centroid += p / 3.0;
    }
    clo = clo.cwiseMin(centroid), chi = chi.cwiseMax(centroid);
  }
  nodes_[static_cast<std::size_t>(node)].lo = lo;
  nodes_[static_cast<std::size_t>(node)].hi = hi;
  if (end - begin <= kLeafSize) {
    nodes_[static_cast<std::size_t>(node)].first = begin;
    nodes_[static_cast<std::size_t>(node)].count = end - begin;
    return;
  }
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const int middle = begin + (end - begin) / 2;
  auto centroid_on_axis = [&](int f) { return V(F_(f, 0), axis) + V(F_(f, 1), axis) + V(F_(f, 2), axis); };
  std::nth_element(faces_.begin() + begin, faces_.begin() + middle, faces_.begin() + end,
                   [&](int a, int b) { return centroid_on_axis(a) < centroid_on_axis(b); });
  const int left = static_cast<int>(nodes_.size());
  nodes_.push_back({});
  nodes_.push_back({});
  nodes_[static_cast<std::size_t>(node)].first = left;
  nodes_[static_cast<std::size_t>(node)].count = 0;
  build(left, begin, middle, V);
  build(left + 1, middle, end, V);
}

void TriangleBvh::fit(int node, const Eigen::MatrixXd& V) {
  Node& n = nodes_[static_cast<std::size_t>(node)];
  if (n.count > 0) {
    n.lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    n.hi = -n.lo;
    for (int k = n.first; k < n.first + n.count; ++k) {
      for (int c = 0; c < 3; ++c) {
        const Eigen::Vector3d p = corner(V, F_, faces_[static_cast<std::size_t>(k)], c);
        n.lo = n.lo.cwiseMin(p), n.hi = n.hi.cwiseMax(p);
      }
    }
    return;
  }
  fit(n.first, V);
  fit(n.first + 1, V);
  const Node& a = nodes_[static_cast<std::size_t>(n.first)];
  const Node& b = nodes_[static_cast<std::size_t>(n.first + 1)];
  n.lo = a.lo.cwiseMin(b.lo);
  n.hi = a.hi.cwiseMax(b.hi);
}

void TriangleBvh::refit(const Eigen::MatrixXd& V) {
  if (!nodes_.empty()) fit(0, V);
}

std::optional<TriangleBvh::Hit> TriangleBvh::closest_point(const Eigen::MatrixXd& V, const Eigen::Vector3d& p,
                                                           double max_distance) const {
  if (nodes_.empty()) return std::nullopt;
  double best2 = max_distance * max_distance;
  Hit best;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[static_cast<std::size_t>(stack[--top])];
    if (box_distance2(p, n.lo, n.hi) > best2) continue;
    if (n.count > 0) {
      for (int k = n.first; k < n.first + n.count; ++k) {
        const int f = faces_[static_cast<std::size_t>(k)];
        const Eigen::Vector3d q =
            closest_point_on_triangle(p, corner(V, F_, f, 0), corner(V, F_, f, 1), corner(V, F_, f, 2));
        const double d2 = (q - p).squaredNorm();
        if (d2 <= best2 && (best.face < 0 || d2 < best2)) best2 = d2, best.face = f, best.point = q;
      }
      continue;
    }
    // Nearer child last so it is popped first.
    const Node& a = nodes_[static_cast<std::size_t>(n.first)];
    const Node& b = nodes_[static_cast<std::size_t>(n.first + 1)];
    const bool a_first = box_distance2(p, a.lo, a.hi) <= box_distance2(p, b.lo, b.hi);
    stack[top++] = a_first ? n.first + 1 : n.first;
    stack[top++] = a_first ? n.first : n.first + 1;
  }
  if (best.face < 0) return std::nullopt;
  best.distance = std::sqrt(best2);
  return best;
}

std::optional<TriangleBvh::Hit> TriangleBvh::ray_hit(const Eigen::MatrixXd& V, const Eigen::Vector3d& origin,
                                                     const Eigen::Vector3d& direction, double max_t) const {
  if (nodes_.empty() || !(direction.squaredNorm() > 0.0)) return std::nullopt;
  const Eigen::Vector3d inverse = direction.cwiseInverse();
  double best_t = max_t;
  int best_face = -1;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[static_cast<std::size_t>(stack[--top])];
    // A missed box has entry +inf, which is <= best_t while nothing is hit yet (best_t = max_t = +inf):
    // without the finiteness check a ray that has not hit yet visits every box.
    const double entry = box_entry(origin, inverse, n.lo, n.hi, best_t);
    if (!(entry < std::numeric_limits<double>::infinity() && entry <= best_t)) continue;
    if (n.count > 0) {
      for (int k = n.first; k < n.first + n.count; ++k) {
        // Moeller-Trumbore, both sides.
        const int f = faces_[static_cast<std::size_t>(k)];
        const Eigen::Vector3d a = corner(V, F_, f, 0), e1 = corner(V, F_, f, 1) - a,
                              e2 = corner(V, F_, f, 2) - a;
        const Eigen::Vector3d pv = direction.cross(e2);
        const double det = e1.dot(pv);
        if (det == 0.0) continue;
        const double inv_det = 1.0 / det;
        const Eigen::Vector3d tv = origin - a;
        const double u = tv.dot(pv) * inv_det;
        if (u < 0.0 || u > 1.0) continue;
        const Eigen::Vector3d qv = tv.cross(e1);
        const double v = direction.dot(qv) * inv_det;
        if (v < 0.0 || u + v > 1.0) continue;
        const double t = e2.dot(qv) * inv_det;
        if (t >= 0.0 && t <= best_t) best_t = t, best_face = f;
      }
      continue;
    }
    const Node& a = nodes_[static_cast<std::size_t>(n.first)];
    const Node& b = nodes_[static_cast<std::size_t>(n.first + 1)];
    const double ta = box_entry(origin, inverse, a.lo, a.hi, best_t);
    const double tb = box_entry(origin, inverse, b.lo, b.hi, best_t);
    stack[top++] = ta <= tb ? n.first + 1 : n.first;
    stack[top++] = ta <= tb ? n.first : n.first + 1;
  }
  if (best_face < 0) return std::nullopt;
  Hit hit;
  hit.face = best_face;
  hit.point = origin + best_t * direction;
  hit.distance = best_t * direction.norm();
  return hit;
}

}  // namespace pushpull::deform
