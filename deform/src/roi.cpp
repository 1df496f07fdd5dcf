// Region of interest: region growing from the handle, explicit regions, selection files (see roi.hpp).
#include "pushpull/deform/roi.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "mesh_graph.hpp"

namespace pushpull::deform {
namespace {

using detail::VertexGraph;

// Sorted unique copy of `indices`, each checked against [0, vertex_count).
std::vector<int> checked_set(std::span<const int> indices, Eigen::Index vertex_count, const char* what,
                             std::vector<std::string>& warnings) {
  std::vector<int> out(indices.begin(), indices.end());
  for (int v : out) {
    if (v < 0 || v >= vertex_count) {
      throw std::invalid_argument(std::string("region of interest: ") + what + " vertex " +
                                  std::to_string(v) + " is out of range [0, " + std::to_string(vertex_count) +
                                  ")");
    }
  }
  std::sort(out.begin(), out.end());
  const auto before = out.size();
  out.erase(std::unique(out.begin(), out.end()), out.end());
  if (out.size() != before) {
    warnings.push_back(std::string("region of interest: ") + std::to_string(before - out.size()) + " " +
                       what + " vertices listed more than once");
  }
  return out;
}

void check_disjoint(const std::vector<int>& handle, const std::vector<int>& fixed) {
  std::vector<int> both;
  std::set_intersection(handle.begin(), handle.end(), fixed.begin(), fixed.end(), std::back_inserter(both));
  if (!both.empty()) {
    throw std::invalid_argument("region of interest: vertex " + std::to_string(both.front()) +
                                " is both a handle and a fixed vertex (" + std::to_string(both.size()) +
                                " such vertices)");
  }
  if (handle.empty()) throw std::invalid_argument("region of interest: the handle set is empty");
}

// Assigns roles from membership in Omega, then warns about handles near fixed vertices.
RegionOfInterest finish(const VertexGraph& graph, const std::vector<char>& in_omega,
                        const std::vector<int>& handle, const std::vector<int>& fixed,
                        const RoiOptions& options, std::vector<std::string> warnings) {
  const int nv = graph.vertex_count();
  RegionOfInterest roi;
  roi.warnings = std::move(warnings);
  roi.role.assign(static_cast<std::size_t>(nv), VertexRole::Outside);
  roi.whole_parts = true;
  for (int v = 0; v < nv; ++v) {
    if (!in_omega[static_cast<std::size_t>(v)]) continue;
    bool on_boundary = false;
    for (const int* n = graph.begin(v); n != graph.end(v); ++n)
      on_boundary |= !in_omega[static_cast<std::size_t>(*n)];
    roi.role[static_cast<std::size_t>(v)] = on_boundary ? VertexRole::Fixed : VertexRole::Free;
    if (on_boundary) roi.whole_parts = false;
  }
  for (int v : fixed) {
    if (in_omega[static_cast<std::size_t>(v)]) roi.role[static_cast<std::size_t>(v)] = VertexRole::Fixed;
  }
  for (int v : handle) roi.role[static_cast<std::size_t>(v)] = VertexRole::Handle;
  for (int v = 0; v < nv; ++v) {
    switch (roi.role[static_cast<std::size_t>(v)]) {
      case VertexRole::Handle:
        roi.handle.push_back(v);
        break;
      case VertexRole::Fixed:
        roi.fixed.push_back(v);
        break;
      case VertexRole::Free:
        roi.free.push_back(v);
        break;
      case VertexRole::Outside:
        break;
    }
  }

  // Rings from the fixed set, inside Omega, up to the warning depth.
  if (options.near_boundary_rings > 0 && !roi.fixed.empty()) {
    std::vector<int> rings(static_cast<std::size_t>(nv), -1);
    std::vector<int> frontier = roi.fixed;
    for (int v : frontier) rings[static_cast<std::size_t>(v)] = 0;
    for (int depth = 1; depth <= options.near_boundary_rings && !frontier.empty(); ++depth) {
      std::vector<int> next;
      for (int v : frontier) {
        for (const int* n = graph.begin(v); n != graph.end(v); ++n) {
          if (roi.role[static_cast<std::size_t>(*n)] == VertexRole::Outside ||
              rings[static_cast<std::size_t>(*n)] >= 0)
            continue;
          rings[static_cast<std::size_t>(*n)] = depth;
          next.push_back(*n);
        }
      }
      frontier = std::move(next);
    }
    int closest = -1, closest_rings = options.near_boundary_rings + 1, count = 0;
    for (int h : roi.handle) {
      const int r = rings[static_cast<std::size_t>(h)];
      if (r < 0) continue;
      ++count;
      if (r < closest_rings) closest = h, closest_rings = r;
    }
    if (count > 0) {
      std::ostringstream msg;
      msg << "region of interest: " << count << " handle vertices lie within " << options.near_boundary_rings
          << " rings of the fixed boundary (closest: vertex " << closest << ", " << closest_rings
          << " rings); the result may differ from what the user expects, consider a larger region";
      roi.warnings.push_back(msg.str());
    }
  }
  return roi;
}

}  // namespace

RegionOfInterest build_roi(const Mesh& mesh, std::span<const int> handle_in, std::span<const int> fixed_in,
                           double max_distance, const RoiOptions& options) {
  if (std::isnan(max_distance) || max_distance < 0) {
    throw std::invalid_argument("build_roi: max_distance must be >= 0 (or infinity), got " +
                                std::to_string(max_distance));
  }
  std::vector<std::string> warnings;
  const Eigen::Index nv = mesh.V.rows();
  const std::vector<int> handle = checked_set(handle_in, nv, "handle", warnings);
  const std::vector<int> fixed = checked_set(fixed_in, nv, "fixed", warnings);
  check_disjoint(handle, fixed);
  const VertexGraph graph = detail::build_vertex_graph(static_cast<int>(nv), mesh.F);

  std::vector<char> is_fixed(static_cast<std::size_t>(nv), 0), in_omega(static_cast<std::size_t>(nv), 0);
  for (int v : fixed) is_fixed[static_cast<std::size_t>(v)] = 1;
  std::vector<double> distance(static_cast<std::size_t>(nv), std::numeric_limits<double>::infinity());
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (int h : handle) {
    distance[static_cast<std::size_t>(h)] = 0;
    queue.emplace(0.0, h);
  }
  while (!queue.empty()) {
    const auto [dist, v] = queue.top();
    queue.pop();
    if (dist > distance[static_cast<std::size_t>(v)] || in_omega[static_cast<std::size_t>(v)]) continue;
    in_omega[static_cast<std::size_t>(v)] = 1;
    if (is_fixed[static_cast<std::size_t>(v)]) continue;  // F bounds the region: do not grow past it
    for (const int* n = graph.begin(v); n != graph.end(v); ++n) {
      const double nd = dist + (mesh.V.row(v) - mesh.V.row(*n)).norm();
      if (nd <= max_distance && nd < distance[static_cast<std::size_t>(*n)]) {
        distance[static_cast<std::size_t>(*n)] = nd;
        queue.emplace(nd, *n);
      }
    }
  }
  return finish(graph, in_omega, handle, fixed, options, std::move(warnings));
}

RegionOfInterest make_roi(const Mesh& mesh, std::span<const int> handle_in, std::span<const int> fixed_in,
                          std::span<const int> region_in, const RoiOptions& options) {
  std::vector<std::string> warnings;
  const Eigen::Index nv = mesh.V.rows();
  const std::vector<int> handle = checked_set(handle_in, nv, "handle", warnings);
  const std::vector<int> fixed = checked_set(fixed_in, nv, "fixed", warnings);
  const std::vector<int> region = checked_set(region_in, nv, "region", warnings);
  check_disjoint(handle, fixed);
  std::vector<char> in_omega(static_cast<std::size_t>(nv), region.empty() ? 1 : 0);
  for (int v : region) in_omega[static_cast<std::size_t>(v)] = 1;
  for (int v : handle) in_omega[static_cast<std::size_t>(v)] = 1;
  for (int v : fixed) in_omega[static_cast<std::size_t>(v)] = 1;
  const VertexGraph graph = detail::build_vertex_graph(static_cast<int>(nv), mesh.F);
  return finish(graph, in_omega, handle, fixed, options, std::move(warnings));
}

RegionOfInterest roi_from_selection(const Mesh& mesh, std::span<const int> selection,
                                    const RoiOptions& options) {
  if (static_cast<Eigen::Index>(selection.size()) != mesh.V.rows()) {
    throw std::invalid_argument("roi_from_selection: " + std::to_string(selection.size()) +
                                " selection values for a mesh of " + std::to_string(mesh.V.rows()) +
                                " vertices");
  }
  std::vector<int> handle, fixed, region;
  for (std::size_t v = 0; v < selection.size(); ++v) {
    const int s = selection[v];
    if (s == 0) fixed.push_back(static_cast<int>(v));
    if (s == 1) region.push_back(static_cast<int>(v));
    if (s == 2) handle.push_back(static_cast<int>(v));
  }
  if (region.empty() && handle.empty() && fixed.empty()) {
    throw std::invalid_argument("roi_from_selection: no vertex is selected (values 0, 1 or 2)");
  }
  std::vector<std::string> warnings;
  check_disjoint(handle, fixed);
  std::vector<char> in_omega(selection.size(), 0);
  for (const auto* list : {&handle, &fixed, &region}) {
    for (int v : *list) in_omega[static_cast<std::size_t>(v)] = 1;
  }
  const VertexGraph graph = detail::build_vertex_graph(static_cast<int>(mesh.V.rows()), mesh.F);
  return finish(graph, in_omega, handle, fixed, options, std::move(warnings));
}

}  // namespace pushpull::deform
