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

// The section curves of one plane (perpendicular to d) before (grey) and after (red), in the plane's own 2D
// axes (u, v): v the model's up where d is not along it, life-size millimetres, one scale for both. The
// caption gives the curves' largest extent in the plane ("across"; within 0.1% of it: the widest of 64
// directions).
std::string section_svg(const deform::Section& section, const Eigen::Vector3d& d, const Eigen::Vector3d& up,
                        double scale) {
  const Eigen::Vector3d n = d.normalized();
  Eigen::Vector3d v = up - up.dot(n) * n;
  if (!(v.norm() > 0.1 * up.norm())) {  // pulled along the up axis: any axis in the plane
    const Eigen::Vector3d helper =
        std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    v = n.cross(helper);
  }
  v.normalize();
  const Eigen::Vector3d u = v.cross(n);
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  constexpr int kDirections = 64;
  std::array<std::pair<double, double>, kDirections> spans;
  spans.fill({1e300, -1e300});
  for (const auto* curves : {&section.before, &section.after})
    for (const deform::SectionCurve& c : *curves)
      for (const Eigen::Vector3d& p : c.points) {
        const double x = p.dot(u), y = p.dot(v);
        x0 = std::min(x0, x), x1 = std::max(x1, x);
        y0 = std::min(y0, y), y1 = std::max(y1, y);
        for (int k = 0; k < kDirections; ++k) {
          const double angle = std::numbers::pi * k / kDirections;
          const double s = x * std::cos(angle) + y * std::sin(angle);
          spans[k] = {std::min(spans[k].first, s), std::max(spans[k].second, s)};
        }
      }
  if (!(x1 >= x0)) return "";
  double across = 0.0;
  for (const auto& [lo, hi] : spans) across = std::max(across, hi - lo);
  const double W = 360, H = 220, margin = 10;
  const double k = std::min((W - 2 * margin) / std::max(x1 - x0, 1e-12), (H - 2 * margin) / std::max(y1 - y0, 1e-12));
  std::ostringstream svg;
  svg << "<figure><svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
      << "\" style=\"border:1px solid #ccc\">";
  auto polyline = [&](const deform::SectionCurve& c, const char* colour) {
    svg << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.5\" points=\"";
    auto point = [&](const Eigen::Vector3d& p) {
      svg << number(margin + (p.dot(u) - x0) * k, "%.1f") << ',' << number(H - margin - (p.dot(v) - y0) * k, "%.1f")
          << ' ';
    };
    for (const Eigen::Vector3d& p : c.points) point(p);
    if (c.closed && !c.points.empty()) point(c.points.front());
    svg << "\"/>";
  };
  for (const deform::SectionCurve& c : section.before) polyline(c, "#888");
  for (const deform::SectionCurve& c : section.after) polyline(c, "#d00");
  svg << "</svg><figcaption>section at " << number(section.offset * scale * 1000.0, "%.0f")
      << " mm along d: before grey, after red (" << number(across * scale * 1000.0, "%.0f") << " mm across)"
      << "</figcaption></figure>\n";
  return svg.str();
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
  h << "<tr><th>method, mu</th><td>" << escape(s.method) << ", " << number(s.mu) << "</td></tr>\n";
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
  h << "</table>\n";
  if (commits.empty())
    h << "<p>No push/pull was committed" << (s.not_committed.empty() ? "" : " (see \"not committed\" above)")
      << ".</p>\n";
  for (const ReportCommit& c : commits) {
    const deform::DeformationMetrics& m = c.metrics;
    const double mm = c.scale * 1000.0;
    h << "<h2>Push/pull " << c.index
      << (c.undone ? " <span class=\"bad\">(undone: not in the final model)</span>" : "")
      << "</h2>\n<table>\n";
    h << "<tr><th>method</th><td>" << escape(c.method) << "</td></tr>\n";
    h << "<tr><th>|d|</th><td>" << number(c.d_mm, "%.1f") << " mm</td></tr>\n";
    h << "<tr><th>iterations</th><td>" << c.iterations << (c.converged ? " (converged)" : " (not converged)")
      << "</td></tr>\n";
    h << "<tr><th>error estimate</th><td>"
      << (c.error_estimate ? number(*c.error_estimate) + " of |d|" : std::string("not given")) << "</td></tr>\n";
    h << "<tr><th>region</th><td>" << c.region_vertices << " vertices; " << c.attached_parts
      << " separate part(s) near it bound to the surface, " << c.attached_moved
      << " of them moved with it</td></tr>\n";
    for (const std::string& warning : c.warnings)
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
    for (const deform::Section& section : m.sections) h << section_svg(section, c.d, c.up, c.scale);
    h << "<br>\n";
    for (const auto& [caption, file] : c.pictures)
      h << "<figure><img src=\"" << escape(file) << "\" alt=\"" << escape(caption) << "\"><figcaption>"
        << escape(caption) << "</figcaption></figure>\n";
  }
  if (!s.eye_images.empty()) {
    h << "<h2>What the eyes saw (at each release and at the end)</h2>\n";
    for (const std::string& file : s.eye_images)
      h << "<figure><img src=\"" << escape(file) << "\"><figcaption>" << escape(file) << "</figcaption></figure>\n";
  }
  h << "</body></html>\n";
  try {
    deform::write_file_atomically(path, h.str());
  } catch (const std::exception& e) {
    throw CommandError(path + ": cannot write the report: " + e.what());
  }
}

}  // namespace pushpull::app
