#include "replay_report.hpp"

#include "band_reversals_text.hpp"
#include "commands.hpp"

#include "pushpull/deform/mesh_io.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

namespace pushpull::app {
namespace {

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string number(double v, const char* format = "%.3g") {
  char text[64];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

// The largest 1, 2 or 5 times a power of ten at most `x` (> 0): a round scale-bar length or factor.
double round_down_125(double x) {
  const double power = std::pow(10.0, std::floor(std::log10(x)));
  for (const double step : {5.0, 2.0, 1.0})
    if (step * power <= x) return step * power;
  return power;
}

// One plane across d, seen along d in the plane's own 2D axes (u, v; v the model's up where d is not along
// it), life-size millimetres: the model's cut before the pull (grey) and the same surface points after it
// (red, Section::carried), their move across d drawn `exaggeration` times (the gaps are millimetres on a view
// of a metre; the factor follows |d| and the view, not the method, so two methods' pictures of one push/pull
// compare). The view frames the part of the cut that moved, as it was before; the caption
// gives the largest gap across d and how far the section's points moved along d, least and most (a section
// carried whole moves along d by one amount), and where the plane lies from p0.
std::string section_svg(const deform::Section& section, const Eigen::Vector3d& d, const Eigen::Vector3d& up,
                        double scale, const std::optional<Eigen::Vector3d>& p0) {
  const Eigen::Vector3d n = d.normalized();
  Eigen::Vector3d v = up - up.dot(n) * n;
  const bool upright = v.norm() > 0.1 * up.norm();
  if (!upright) {  // pulled along the up axis: any axis in the plane
    const Eigen::Vector3d helper =
        std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    v = n.cross(helper);
  }
  v.normalize();
  const Eigen::Vector3d u = v.cross(n);
  const double mm = scale * 1000.0;
  struct Box {
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    void add(double x, double y) {
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    [[nodiscard]] bool empty() const { return !(x1 >= x0); }
  };
  Box all, moved;
  double largest_gap = 0.0, largest_move = 0.0;
  double least_along = 1e300, most_along = -1e300;  // of the points that moved
  const bool carried = section.carried.size() == section.before.size();
  for (std::size_t c = 0; c < section.before.size(); ++c)
    for (const Eigen::Vector3d& p : section.before[c].points) all.add(p.dot(u), p.dot(v));
  if (all.empty()) return "";
  if (carried)
    for (std::size_t c = 0; c < section.before.size(); ++c)
      for (std::size_t k = 0; k < section.before[c].points.size() && k < section.carried[c].points.size();
           ++k)
        largest_move =
            std::max(largest_move, (section.carried[c].points[k] - section.before[c].points[k]).norm());
  // The moved part: points that moved more than 1% of the largest move (or 0.1 mm); framed as they were.
  const double threshold = std::max(0.01 * largest_move, 1e-4 / scale);
  if (carried)
    for (std::size_t c = 0; c < section.before.size(); ++c)
      for (std::size_t k = 0; k < section.before[c].points.size() && k < section.carried[c].points.size();
           ++k) {
        const Eigen::Vector3d& a = section.before[c].points[k];
        const Eigen::Vector3d move = section.carried[c].points[k] - a;
        if (move.norm() <= threshold) continue;
        moved.add(a.dot(u), a.dot(v));
        largest_gap = std::max(largest_gap, (move - move.dot(n) * n).norm());
        least_along = std::min(least_along, move.dot(n));
        most_along = std::max(most_along, move.dot(n));
      }
  Box view = all;
  if (!moved.empty()) {  // the moved part with a margin of context, within the whole cut
    const double size = std::max(
        {moved.x1 - moved.x0, moved.y1 - moved.y0, 0.05 * std::max(all.x1 - all.x0, all.y1 - all.y0)});
    const double margin = 0.3 * size;
    view.x0 = std::max(all.x0, moved.x0 - margin), view.x1 = std::min(all.x1, moved.x1 + margin);
    view.y0 = std::max(all.y0, moved.y0 - margin), view.y1 = std::min(all.y1, moved.y1 + margin);
    view.add(moved.x0, moved.y0), view.add(moved.x1, moved.y1);
  }
  const double W = 360, H = 220, margin = 10;
  const double k = std::min((W - 2 * margin) / std::max(view.x1 - view.x0, 1e-12),
                            (H - 2 * margin) / std::max(view.y1 - view.y0, 1e-12));
  // A gap of 5% of |d| drawn as 8% of the view's width: 1, 2 or 5 times a power of ten, at least 1.
  const double view_width = (W - 2 * margin) / k;  // model units
  const double wanted = d.norm() > 0.0 ? 0.08 * view_width / (0.05 * d.norm()) : 1.0;
  const double exaggeration = std::clamp(round_down_125(std::max(wanted, 1.0)), 1.0, 1e6);
  // Centred in the picture.
  const double cx = 0.5 * (view.x0 + view.x1), cy = 0.5 * (view.y0 + view.y1);
  auto px = [&](double x) { return 0.5 * W + (x - cx) * k; };
  auto py = [&](double y) { return 0.5 * H - (y - cy) * k; };
  std::ostringstream svg;
  svg << "<figure><svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
      << "\" style=\"border:1px solid #ccc;overflow:hidden\">";
  auto polyline = [&](const std::vector<Eigen::Vector2d>& points, bool closed, const char* colour) {
    svg << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.5\" points=\"";
    auto point = [&](const Eigen::Vector2d& p) {
      svg << number(px(p.x()), "%.1f") << ',' << number(py(p.y()), "%.1f") << ' ';
    };
    for (const Eigen::Vector2d& p : points) point(p);
    if (closed && !points.empty()) point(points.front());
    svg << "\"/>";
  };
  for (std::size_t c = 0; c < section.before.size(); ++c) {
    std::vector<Eigen::Vector2d> grey;
    for (const Eigen::Vector3d& p : section.before[c].points) grey.emplace_back(p.dot(u), p.dot(v));
    polyline(grey, section.before[c].closed, "#888");
  }
  if (carried)
    for (std::size_t c = 0; c < section.before.size(); ++c) {
      std::vector<Eigen::Vector2d> red;
      const auto& before = section.before[c].points;
      const auto& after = section.carried[c].points;
      for (std::size_t q = 0; q < before.size() && q < after.size(); ++q) {
        const Eigen::Vector3d shown = before[q] + exaggeration * (after[q] - before[q]);  // along d: not seen
        red.emplace_back(shown.dot(u), shown.dot(v));
      }
      polyline(red, section.before[c].closed, "#d00");
    }
  // Scale bar, bottom left.
  const double view_mm = view_width * mm;
  const double bar_mm = round_down_125(view_mm > 0.0 ? view_mm / 5.0 : 1.0);
  const double bar_px = bar_mm / mm * k;
  svg << "<line x1=\"" << margin << "\" y1=\"" << H - margin << "\" x2=\"" << number(margin + bar_px, "%.1f")
      << "\" y2=\"" << H - margin << "\" stroke=\"#000\" stroke-width=\"2\"/><text x=\"" << margin
      << "\" y=\"" << H - margin - 4 << "\" font-size=\"11\">" << number(bar_mm, "%g") << " mm</text>";
  std::string where = number(section.offset * mm, "%.0f") + " mm along d";
  if (p0) {
    const double from_p0 = (section.offset - p0->dot(n)) * mm;
    where =
        number(std::abs(from_p0), "%.0f") + " mm " + (from_p0 >= 0.0 ? "ahead of" : "behind") + " p0 along d";
  }
  svg << "</svg><figcaption>section " << where << ", seen along d"
      << (upright ? " (the model's up is up)" : "");
  if (!carried)
    svg << ": before grey";
  else if (moved.empty())
    svg << ": before grey; nothing of it moved";
  else
    svg << ": before grey, the same surface points after red, their move across d drawn x"
        << number(exaggeration, "%g") << "; up to " << number(largest_gap * mm, "%.1f")
        << " mm across d, and along d from " << number(least_along * mm, "%.1f") << " to "
        << number(most_along * mm, "%.1f") << " mm";
  svg << "</figcaption></figure>\n";
  return svg.str();
}

// The method as the paper names it (section 3.3 and 4), with its parameter where it has one: "arap-sr" was
// easy to take for "sr-arap", and mu means nothing to the isotropic methods.
std::string method_title(const std::string& method, double mu) {
  static const std::pair<const char*, const char*> kPaperNames[] = {
      {"asan", "ASAN: ARAP-s&r with the region's cotangent weights taken stretched along d"},
      {"arap-s", "ARAP-s: spokes"},
      {"arap-sr", "ARAP-s&r: spokes and rims"},
      {"arap-m", "ARAP-m: per-triangle rotations, membrane"},
      {"arap-n", "ARAP-n: spokes and n-rings"},
      {"sr-arap", "SR-ARAP: smoothed rotations"},
      {"arap-h", "ARAP-h: ARAP-m with a mean-curvature term"},
      {"arap-sr-h", "ARAP-s&r with ARAP-h's mean-curvature term (pushpull's variant)"}};
  std::string title = method;
  for (const auto& [name, paper] : kPaperNames)
    if (method == name) title += std::string(" (") + paper + ")";
  if (method == "asan")
    title += ", mu = " + number(mu, "%g") + (mu == 100.0 ? " (the paper's, section 4.4)" : "");
  return title;
}

// What the numbers and pictures below mean, once, for a reader who has not read the paper.
void how_to_read(std::ostringstream& h) {
  h << "<details open><summary><b>How to read this report</b></summary><ul>\n"
       "<li><b>Push/pull</b>: the reviewer pressed the trigger on the surface at p0, dragged and released at "
       "p1; d = p1 - p0. The handle (the surface around p0) moved by d, a region around it deformed by the "
       "method and its border stayed fixed (Le Vaou et al., Computer-Aided Design 121, 2020).</li>\n"
       "<li><b>Displacement along d and across d</b>: every vertex's move split into its part along the pull "
       "and its part across it (the paper's Fig. 13). ASAN is built to keep the part across d small (its "
       "material is stiff across d, soft along it), so it says how much the surface moved sideways, not by "
       "itself whether the style was kept. RMS is over the region's vertices, its fixed border "
       "included.</li>\n"
       "<li><b>Gaussian curvature sign reversals</b> (the paper's criterion for the style kept, section 5): "
       "vertices of the region (its fixed border included; those on the mesh's boundary or a non-manifold "
       "edge left out) whose surface went from dome-like (K &gt; 0, yellow) to saddle-like (K &lt; 0, blue) "
       "or back: a convex bonnet turned saddle shows here (requirement R2). Fewer is better; a convex "
       "surface "
       "turned concave keeps K &gt; 0 and does not show. Near-flat vertices (|K| L&sup2; &le; 0.01, L the "
       "model's bounding-box diagonal: a curvature radius over L / 0.1; grey in the pictures) count as "
       "neither; \"any sign change\" adds the moves into and out of flat, and \"where clearly curved\" "
       "counts "
       "again among the vertices curved tighter than the given radius before the pull.</li>\n"
       "<li><b>Sections</b>: planes across d at three places along the region (placed from p0), seen along "
       "d: "
       "the cut before the pull (grey) and the same surface points after it (red), their move across d drawn "
       "enlarged by the factor given (the same for every method on one push/pull). Where red leaves grey the "
       "section moved across d: bent, or shifted whole. A move along d does not show in the picture; the "
       "caption gives its least and most: the paper's sections across d stay rigid, so a section carried "
       "whole moves along d by one amount.</li>\n"
       "<li><b>Iterations, converged, error estimate</b>: the solver's estimate of the largest distance of "
       "any vertex to the exact minimiser of the method's energy, as a fraction of |d| and in mm; converged "
       "means it fell below the tolerance (1% of |d| by default).</li>\n"
       "<li><b>Hash</b>: \"match\" means the replayed model is bit for bit the one the review committed; "
       "replayed with another method the hashes are not compared, and \"match (d)\" says the push/pull's d "
       "was the recording's.</li>\n"
       "<li><b>Pictures</b>: before and after with the model's materials; how far each vertex moved in this "
       "push/pull (legend in mm; the colour map's top, red, is |d|, as the paper sets it, so a colour is the "
       "same move in every commit and method, and a vertex moved farther is red too); the curvature sign "
       "before and after (yellow +, blue -, grey near-flat or on an edge, not measured), and where it "
       "reversed (the reversals counted above, in the colour of the new sign; grey: "
       "kept); the magenta arrow is d, from p0 to p1. The camera looks at the push/pull's region along the "
       "surface at p0, the same before and after.</li>\n"
       "</ul></details>\n";
}

}  // namespace

void write_replay_report(const std::string& path, const ReportSession& s, const std::vector<ReportCommit>& commits) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>pushpull replay: " << escape(s.recording)
    << "</title>\n<style>body{font-family:sans-serif;margin:2em;max-width:1200px}table{border-collapse:collapse}"
       "td,th{border:1px solid #ccc;padding:3px 8px;text-align:left}img{max-width:290px;margin:2px}"
       "figure{display:inline-block;margin:4px}figcaption{font-size:85%}.bad{color:#b00}.ok{color:#070}"
       "</style></head><body>\n";
  h << "<h1>pushpull replay</h1>\n<table>\n";
  h << "<tr><th>recording</th><td>" << escape(s.recording) << "</td></tr>\n";
  h << "<tr><th>model</th><td>" << escape(s.model) << "</td></tr>\n";
  h << "<tr><th>model SHA-256</th><td><code>" << escape(s.model_sha256) << "</code></td></tr>\n";
  h << "<tr><th>recorded on</th><td>" << escape(s.runtime) << "</td></tr>\n";
  h << "<tr><th>method</th><td>" << escape(method_title(s.method, s.mu)) << "</td></tr>\n";
  h << "<tr><th>result</th><td>" << escape(s.summary) << "</td></tr>\n";
  if (!s.history.empty()) h << "<tr><th>history</th><td>" << escape(s.history) << "</td></tr>\n";
  if (!s.final_model.empty()) h << "<tr><th>final model</th><td>" << escape(s.final_model) << "</td></tr>\n";
  if (!s.not_committed.empty()) {
    h << "<tr><th>not committed</th><td class=\"bad\">" << s.not_committed.size()
      << " push/pull(s) the solver could not commit (the model stayed as it was):<ul>";
    for (const std::string& error : s.not_committed) h << "<li>" << escape(error) << "</li>";
    h << "</ul></td></tr>\n";
  }
  if (!s.cut.empty()) h << "<tr><th>recording cut</th><td class=\"bad\">" << escape(s.cut) << "</td></tr>\n";
  // The model's own notes (the weld's non-manifold edges, degenerate faces, its parts: "mesh: ...") are the
  // same for every commit: said once here, not in red under each push/pull.
  std::vector<std::string> model_notes;
  if (!commits.empty())
    for (const std::string& w : commits.front().warnings)
      if (w.rfind("mesh: ", 0) == 0 &&
          std::all_of(commits.begin(), commits.end(), [&](const ReportCommit& c) {
            return std::find(c.warnings.begin(), c.warnings.end(), w) != c.warnings.end();
          }))
        model_notes.push_back(w);
  if (!model_notes.empty()) {
    h << "<tr><th>model notes</th><td>what the solver tolerates in this model (the same for every "
         "push/pull):<ul>";
    for (const std::string& note : model_notes) h << "<li>" << escape(note.substr(6)) << "</li>";
    h << "</ul></td></tr>\n";
  }
  h << "</table>\n";
  how_to_read(h);
  if (commits.empty())
    h << "<p>No push/pull was committed" << (s.not_committed.empty() ? "" : " (see \"not committed\" above)")
      << ".</p>\n";
  for (const ReportCommit& c : commits) {
    const deform::DeformationMetrics& m = c.metrics;
    const double mm = c.scale * 1000.0;
    h << "<h2>Push/pull " << c.index
      << (c.undone ? " <span class=\"bad\">(undone: not in the final model)</span>" : "")
      << "</h2>\n<table>\n";
    h << "<tr><th>method</th><td>" << escape(method_title(c.method, s.mu)) << "</td></tr>\n";
    h << "<tr><th>|d|</th><td>" << number(c.d_mm, "%.1f") << " mm</td></tr>\n";
    h << "<tr><th>iterations</th><td>" << c.iterations << (c.converged ? " (converged)" : " (not converged)")
      << "</td></tr>\n";
    h << "<tr><th>error estimate</th><td>"
      << (c.error_estimate
              ? number(*c.error_estimate) + " of |d| (" + number(*c.error_estimate * c.d_mm, "%.2f") + " mm)"
              : std::string("not given"))
      << "</td></tr>\n";
    if (c.handle_radius_mm || c.angle_to_normal_deg) {
      h << "<tr><th>grabbed</th><td>";
      if (c.handle_radius_mm)
        h << "the handle within " << number(*c.handle_radius_mm, "%.0f") << " mm of p0 along the surface ("
          << c.handle_vertices << (c.handle_vertices == 1 ? " vertex)" : " vertices)")
          << (c.roi_radius_mm ? ", the region " + number(*c.roi_radius_mm, "%.0f") + " mm further" : "")
          << "; ";
      if (c.angle_to_normal_deg)
        h << "d at " << number(*c.angle_to_normal_deg, "%.0f") << "&deg; to the surface normal at p0 ("
          << (*c.angle_to_normal_deg < 30.0   ? "a push or pull across the surface"
              : *c.angle_to_normal_deg > 60.0 ? "mostly a drag along the surface"
                                              : "oblique")
          << ")";
      h << "</td></tr>\n";
    }
    h << "<tr><th>region</th><td>" << c.region_vertices << " vertices; " << c.attached_parts
      << " separate part(s) near it bound to the surface, " << c.attached_moved
      << " of them moved with it</td></tr>\n";
    for (const std::string& warning : c.warnings)
      if (std::find(model_notes.begin(), model_notes.end(), warning) == model_notes.end())
        h << "<tr><th>warning</th><td class=\"bad\">" << escape(warning) << "</td></tr>\n";
    if (m.curvature_vertices == 0)  // a strip of a region: no vertex with its whole ring inside, no measure
      h << "<tr><th>Gaussian curvature sign reversals</th><td>not measured (no interior vertex in the region)"
        << "</td></tr>\n";
    else
      h << "<tr><th>Gaussian curvature sign reversals</th><td>" << m.sign_reversals << " of "
        << m.curvature_vertices << " vertices (" << number(100.0 * m.sign_reversal_fraction)
        << " %); any sign change " << m.sign_flips << "</td></tr>\n";
    if (m.curvature_vertices > 0 && !m.reversals_by_band.empty())
      h << "<tr><th>reversals where clearly curved</th><td>"
        << escape(describe_band_reversals(m.reversals_by_band, c.scale)) << "</td></tr>\n";
    h << "<tr><th>displacement along d</th><td>RMS " << number(m.along_d.rms * mm) << " mm, max "
      << number(m.along_d.max * mm) << " mm</td></tr>\n";
    h << "<tr><th>displacement across d</th><td>RMS " << number(m.orthogonal.rms * mm) << " mm, max "
      << number(m.orthogonal.max * mm) << " mm</td></tr>\n";
    h << "<tr><th>largest displacement</th><td>" << number(m.displacement.max * mm) << " mm</td></tr>\n";
    h << "<tr><th>hash</th><td><code>" << escape(c.hash) << "</code> <span class=\""
      << (c.check.rfind("match", 0) == 0 ? "ok" : "bad") << "\">" << escape(c.check) << "</span></td></tr>\n";
    h << "<tr><th>files</th><td><a href=\"" << escape(c.model_file) << "\">" << escape(c.model_file)
      << "</a>, <a href=\"" << escape(c.metrics_file) << "\">" << escape(c.metrics_file) << "</a></td></tr>\n";
    h << "</table>\n";
    for (const deform::Section& section : m.sections) h << section_svg(section, c.d, c.up, c.scale, c.p0);
    h << "<br>\n";
    for (const auto& [caption, file] : c.pictures)
      h << "<figure><img src=\"" << escape(file) << "\" alt=\"" << escape(caption) << "\"><figcaption>"
        << escape(caption) << "</figcaption></figure>\n";
  }
  if (!s.eye_images.empty()) {
    h << "<h2>What the eyes saw (at each release and at the end)</h2>\n";
    for (std::size_t k = 0; k < s.eye_images.size(); ++k)
      h << "<figure><img src=\"" << escape(s.eye_images[k]) << "\"><figcaption>"
        << escape(k < s.eye_captions.size() ? s.eye_captions[k] : s.eye_images[k])
        << "</figcaption></figure>\n";
  }
  h << "</body></html>\n";
  try {
    deform::write_file_atomically(path, h.str());
  } catch (const std::exception& e) {
    throw CommandError(path + ": cannot write the report: " + e.what());
  }
}

}  // namespace pushpull::app
