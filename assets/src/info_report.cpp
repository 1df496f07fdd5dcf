#include "pushpull/assets/info.hpp"

#include "pushpull/deform/mesh_components.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

namespace pushpull::assets {

namespace {

std::string number(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

// A bound's coordinate to 1e-6 of the model's size: a model far from its file's origin (site coordinates,
// 1e6 m away) keeps the digits that say where it ends ("%.6g" printed 999999 and 1e+06 for a 1.5 m part).
std::string coordinate(double value, double size) {
  const double resolution = size > 0.0 ? 1e-6 * size : 1e-6 * std::abs(value);
  int digits = 6;
  if (resolution > 0.0 && std::abs(value) > resolution)
    digits = std::clamp(int(std::ceil(std::log10(std::abs(value) / resolution))), 6, 17);
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) {
    if (!out.empty()) out += ", ";
    out += item;
  }
  return out.empty() ? "none" : out;
}

// The deform mesh's connected components (deform::face_components) renumbered by decreasing size (0 the
// largest; vertices counted); `sizes` by the new numbers.
std::vector<int> components_by_size(const deform::Mesh& mesh, std::vector<std::size_t>& sizes) {
  std::vector<int> labels = deform::face_components(mesh);
  std::vector<std::size_t> count;
  for (const int label : labels) {
    if (static_cast<std::size_t>(label) >= count.size()) count.resize(static_cast<std::size_t>(label) + 1, 0);
    ++count[static_cast<std::size_t>(label)];
  }
  std::vector<int> order(count.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return count[static_cast<std::size_t>(a)] > count[static_cast<std::size_t>(b)];
  });
  std::vector<int> renumbered(count.size());
  sizes.assign(count.size(), 0);
  for (std::size_t rank = 0; rank < order.size(); ++rank) {
    renumbered[static_cast<std::size_t>(order[rank])] = static_cast<int>(rank);
    sizes[rank] = count[static_cast<std::size_t>(order[rank])];
  }
  for (int& label : labels) label = renumbered[static_cast<std::size_t>(label)];
  return labels;
}

// The node (or mesh) a primitive belongs to, as a user names the part: "<node name>" of
// "<node name>/<mesh name>#<primitive>".
std::string part_name(const Primitive& p) {
  const std::string& name = p.name;
  const std::size_t slash = name.find('/');
  std::string part = slash == std::string::npos ? name : name.substr(0, slash);
  if (part.empty()) part = name.substr(0, name.find('#'));
  if (!part.empty()) return part;
  std::ostringstream unnamed;  // (a string concatenation here trips GCC 12's -Wrestrict)
  unnamed << "node " << p.node;
  return unnamed.str();
}

// The components the weld made of more than one part (glTF node): which parts a pull on one drags along as
// one surface (a lamp's reflector sharing the body's vertices is the body), and the parts the weld split
// between such a component and others (half of a lens joined to the body). Empty for a file of one part.
std::string describe_joined_parts(const Model& model) {
  if (model.primitives.size() < 2) return "";
  std::vector<std::size_t> sizes;
  const std::vector<int> labels = components_by_size(model.deform_mesh, sizes);
  // Per part: its deform vertices, and how many of them lie in each component.
  std::map<std::string, std::set<int>> vertices_of_part;
  for (const Primitive& p : model.primitives)
    for (const int v : p.deform_vertex)
      if (v >= 0 && static_cast<std::size_t>(v) < labels.size() && labels[static_cast<std::size_t>(v)] >= 0)
        vertices_of_part[part_name(p)].insert(v);
  std::map<int, std::vector<std::pair<std::string, std::pair<std::size_t, std::size_t>>>> parts_in;  // in, of
  for (const auto& [part, vertices] : vertices_of_part) {
    std::map<int, std::size_t> in;
    for (const int v : vertices) ++in[labels[static_cast<std::size_t>(v)]];
    for (const auto& [component, count] : in) parts_in[component].push_back({part, {count, vertices.size()}});
  }
  std::ostringstream out;
  constexpr std::size_t kComponents = 6, kParts = 10;
  std::size_t shown = 0, more = 0;
  for (const auto& [component, parts] : parts_in) {
    if (parts.size() < 2) continue;
    if (shown == kComponents) {
      ++more;
      continue;
    }
    ++shown;
    out << "  - component " << component << " (" << sizes[static_cast<std::size_t>(component)]
        << " vertices): " << parts.size() << " parts, one surface: ";
    auto sorted = parts;  // the largest share first
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const auto& x, const auto& y) { return x.second.first > y.second.first; });
    for (std::size_t k = 0; k < sorted.size() && k < kParts; ++k) {
      const auto& [part, share] = sorted[k];
      out << (k ? ", " : "") << part;
      if (share.first < share.second)
        out << " (" << share.first << " of its " << share.second << " vertices)";
    }
    if (sorted.size() > kParts) out << ", and " << sorted.size() - kParts << " more";
    out << "\n";
  }
  if (shown == 0) return "";
  std::ostringstream head;
  head << "joined:       parts (glTF nodes) the weld made one surface, which a pull deforms together ("
          "--no-attached-parts leaves only separate parts behind):\n"
       << out.str();
  if (more > 0) head << "  - and " << more << " more component(s) of several parts\n";
  return head.str();
}

}  // namespace

std::string describe_model(const Model& model) {
  std::ostringstream out;
  const LoadReport& report = model.report;
  const WeldStats& weld = report.weld;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  if (!model.bounds.isEmpty()) size = model.bounds.sizes();
  out << "model:        " << model.source_path.string() << " (" << report.format << ")\n";
  out << "size:         " << number(size.x()) << " x " << number(size.y()) << " x " << number(size.z())
      << (model.source ? " (file units, glTF: m; longest side " : " (file units; longest side ")
      << number(size.maxCoeff()) << ")\n";
  if (!model.bounds.isEmpty()) {
    const double across = size.maxCoeff();
    auto at = [&](const Eigen::Vector3d& p) {
      out << '(' << coordinate(p.x(), across) << ", " << coordinate(p.y(), across) << ", "
          << coordinate(p.z(), across) << ')';
    };
    out << "bounds:       min ";
    at(model.bounds.min());
    out << " max ";
    at(model.bounds.max());
    out << '\n';
  }
  out << "scale:        " << number(model.scale) << " (life size: longest side "
      << number(size.maxCoeff() * model.scale) << " m)\n";
  std::set<int> nodes, meshes;
  for (const Primitive& p : model.primitives) {
    if (p.node >= 0) nodes.insert(p.node);
    if (p.mesh >= 0) meshes.insert(p.mesh);
  }
  out << "render:       " << model.primitives.size() << " primitive instance(s)";
  if (!meshes.empty()) out << " of " << meshes.size() << " mesh(es) on " << nodes.size() << " node(s)";
  out << ", " << weld.render_vertices << " vertices, " << weld.render_triangles << " triangles\n";
  out << "materials:    " << model.materials.size();
  for (std::size_t i = 0; i < model.materials.size(); ++i) {
    const Material& m = model.materials[i];
    out << (i == 0 ? " (" : ", ");
    if (m.name.empty())
      out << '#' << i;
    else
      out << m.name;
    if (!m.extensions.empty()) out << " [" << join(m.extensions) << "]";
    if (i + 1 == model.materials.size()) out << ")";
  }
  out << "\n";
  std::size_t missing = 0;
  for (const Image& image : model.images) missing += image.missing ? 1 : 0;
  out << "textures:     " << model.textures.size() << " textures, " << model.images.size() << " images";
  if (missing) out << " (" << missing << " missing)";
  out << "\n";
  out << "extensions:   used " << join(report.extensions_used) << "; required "
      << join(report.extensions_required) << "\n";
  out << "unsupported:  " << join(report.unsupported_extensions) << "\n";
  out << "weld:         tolerance " << number(weld.tolerance) << " (file units); " << weld.render_vertices
      << " -> " << weld.deform_vertices << " vertices; " << weld.pieces_before << " pieces -> "
      << weld.topology.components << " components; " << weld.collapsed_triangles
      << " triangles collapsed by the weld or repeating a corner in the file (dropped)\n";
  out << "deform mesh:  " << model.deform_mesh.V.rows() << " vertices, " << model.deform_mesh.F.rows()
      << " triangles, " << weld.topology.components << " components, " << weld.topology.boundary_loops
      << " boundary loops (" << weld.topology.boundary_edges << " boundary edges), "
      << weld.topology.non_manifold_edges << " non-manifold edges, " << weld.topology.degenerate_triangles
      << " degenerate triangles (repeated vertex or zero area: no stiffness in the solver)\n";
  std::size_t unused = 0;  // (each primitive's own; an instanced mesh counts once per instance)
  for (const Primitive& p : model.primitives)
    unused += static_cast<std::size_t>(std::count(p.deform_vertex.begin(), p.deform_vertex.end(), -1));
  if (unused > 0)
    out << "unused:       " << unused
        << " vertices of the file are used by no triangle (left out of the drawn and deformed surface)\n";
  out << describe_joined_parts(model);
  out << "warnings:     " << report.warnings.size() << "\n";
  for (const std::string& warning : report.warnings) out << "  - " << warning << "\n";
  return out.str();
}

}  // namespace pushpull::assets
