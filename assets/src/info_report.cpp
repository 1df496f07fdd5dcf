#include "pushpull/assets/info.hpp"

#include <cstdio>
#include <set>
#include <sstream>

namespace pushpull::assets {

namespace {

std::string number(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6g", value);
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

}  // namespace

std::string describe_model(const Model& model) {
  std::ostringstream out;
  const LoadReport& report = model.report;
  const WeldStats& weld = report.weld;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  if (!model.bounds.isEmpty()) size = model.bounds.sizes();
  out << "model:        " << model.source_path.string() << " (" << report.format << ")\n";
  out << "size:         " << number(size.x()) << " x " << number(size.y()) << " x " << number(size.z())
      << " (file units, glTF: m; longest side " << number(size.maxCoeff()) << ")\n";
  if (!model.bounds.isEmpty())
    out << "bounds:       min (" << number(model.bounds.min().x()) << ", " << number(model.bounds.min().y())
        << ", " << number(model.bounds.min().z()) << ") max (" << number(model.bounds.max().x()) << ", "
        << number(model.bounds.max().y()) << ", " << number(model.bounds.max().z()) << ")\n";
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
      << " triangles collapsed by the weld (dropped)\n";
  out << "deform mesh:  " << model.deform_mesh.V.rows() << " vertices, " << model.deform_mesh.F.rows()
      << " triangles, " << weld.topology.components << " components, " << weld.topology.boundary_loops
      << " boundary loops (" << weld.topology.boundary_edges << " boundary edges), "
      << weld.topology.non_manifold_edges << " non-manifold edges, " << weld.topology.degenerate_triangles
      << " degenerate triangles (repeated vertex or zero area: no stiffness in the solver)\n";
  out << "warnings:     " << report.warnings.size() << "\n";
  for (const std::string& warning : report.warnings) out << "  - " << warning << "\n";
  return out.str();
}

}  // namespace pushpull::assets
