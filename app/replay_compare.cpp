#include "replay_compare.hpp"

#include "band_reversals_text.hpp"
#include "commands.hpp"

#include "pushpull/deform/mesh_io.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace pushpull::app {
namespace {

namespace fs = std::filesystem;

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : c == '"' ? "&quot;" : std::string(1, c);
  return out;
}

std::string number(double v, const char* format = "%.3g") {
  char text[64];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

// The reversals_by_band of a METRICS.json curvature object as text (empty when absent: older reports).
std::string band_reversals(const nlohmann::json& curvature, double metres_per_unit) {
  const auto found = curvature.find("reversals_by_band");
  if (found == curvature.end() || !found->is_array() || found->empty()) return {};
  std::vector<deform::BandReversals> bands;
  for (const nlohmann::json& entry : *found) {
    deform::BandReversals band;
    band.band = entry.value("band", 0.0);
    band.radius_below = entry.value("radius_below", 0.0);
    band.compared = entry.value("compared", std::size_t{0});
    band.reversals = entry.value("reversals", std::size_t{0});
    bands.push_back(band);
  }
  return "<br>where clearly curved: " + escape(describe_band_reversals(bands, metres_per_unit));
}

}  // namespace

void run_replay_comparison(const ReplayOptions& o, const std::vector<std::string>& methods) {
  if (methods.size() < 2) throw UsageError("--compare: name at least two methods, e.g. asan,arap-sr");
  const std::string exe = fs::read_symlink("/proc/self/exe").string();
  std::string common = " --eye-size " + std::to_string(o.eye_size.at(0)) + " " + std::to_string(o.eye_size.at(1)) +
                       " --picture-size " + std::to_string(o.picture_size.at(0)) + " " +
                       std::to_string(o.picture_size.at(1));
  if (!o.model.empty()) common += " --model " + quoted(o.model);
  if (o.mu) common += " --mu " + number(*o.mu, "%.17g");
  if (!o.pictures) common += " --no-pictures";
  std::string failed;
  for (const std::string& m : methods) {
    std::printf("pushpull replay: --compare: %s\n", m.c_str());
    std::fflush(stdout);
    const std::string command = quoted(exe) + " replay " + quoted(o.recording) + " --out " +
                                quoted((fs::path(o.out) / m).string()) + " --method " + quoted(m) + common;
    if (std::system(command.c_str()) != 0 && failed.empty()) failed = m;
  }

  // Side by side: one row per push/pull, one column per method.
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>pushpull replay: methods compared</title>\n"
       "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}td,th{border:1px solid #ccc;"
       "padding:4px;vertical-align:top}img{width:300px;display:block}</style></head><body>\n";
  h << "<h1>" << escape(o.recording) << ": methods side by side</h1>\n";
  h << "<p>Each column replays the session's push/pulls with one method. For each push/pull the fewest "
       "Gaussian "
       "curvature sign reversals (the paper's criterion for the style kept, section 5: a bonnet turning "
       "saddle) and the least displacement across d (what ASAN is built to keep small: its material is stiff "
       "across d) are in <b>bold</b>; where they disagree, neither method kept the shape clearly better. The "
       "displacement along d is how the pull spread over the region, better neither way. Each method goes on "
       "from its own results: a push/pull after the first starts from that method's shape, so later rows "
       "compare the methods on surfaces that may already differ (each report's <i>region</i> row gives its "
       "size), and each report gives its section pictures and warnings.</p>\n<table>\n"
       "<tr><th>push/pull</th>";
  for (const std::string& m : methods)
    h << "<th>" << escape(m) << " (<a href=\"" << escape(m) << "/report.html\">report</a>)</th>";
  h << "</tr>\n";
  struct Cell {
    bool present = false, parsed = false;
    nlohmann::json j;
  };
  for (int i = 1;; ++i) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "commit-%02d", i);
    std::vector<Cell> cells(methods.size());
    bool any = false;
    for (std::size_t k = 0; k < methods.size(); ++k) {
      std::ifstream in(fs::path(o.out) / methods[k] / (std::string(stem) + ".metrics.json"));
      if (!in) continue;
      any = cells[k].present = true;
      cells[k].j = nlohmann::json::parse(in, nullptr, false);
      cells[k].parsed = !cells[k].j.is_discarded() && cells[k].j.is_object();
    }
    if (!any) break;
    const auto norm = [](const nlohmann::json& j, const char* part, const char* which) {
      const double scale = j.value("life_size_scale", 1.0);
      if (!j.contains("norms") || !j["norms"].is_object()) return 0.0;
      const auto& norms = j["norms"];
      return norms.contains(part) && norms[part].is_object() ? 1000.0 * scale * norms[part].value(which, 0.0)
                                                             : 0.0;
    };
    const auto reversals = [](const nlohmann::json& j) -> std::optional<long> {
      if (!j.contains("curvature") || !j["curvature"].is_object() ||
          j["curvature"].value("evaluated_vertices", 0) == 0)
        return std::nullopt;
      return j["curvature"].value("sign_reversals", 0L);
    };
    // The best of the row, per criterion, among the methods that have it.
    std::optional<long> fewest;
    std::optional<double> least_across;
    for (const Cell& c : cells) {
      if (!c.parsed) continue;
      if (const auto r = reversals(c.j)) fewest = fewest ? std::min(*fewest, *r) : *r;
      const double across = norm(c.j, "orthogonal", "rms");
      least_across = least_across ? std::min(*least_across, across) : across;
    }
    auto bold = [](bool best, const std::string& text) { return best ? "<b>" + text + "</b>" : text; };
    h << "<tr><th>Push/pull " << i << "</th>";
    for (std::size_t k = 0; k < methods.size(); ++k) {
      h << "<td>";
      const Cell& c = cells[k];
      if (c.parsed) {
        const nlohmann::json& j = c.j;
        const double scale = j.value("life_size_scale", 1.0);
        double d_mm = 0.0;
        if (j.contains("d") && j["d"].is_array() && j["d"].size() == 3)
          d_mm = 1000.0 * scale *
                 std::sqrt(double(j["d"][0]) * double(j["d"][0]) + double(j["d"][1]) * double(j["d"][1]) +
                           double(j["d"][2]) * double(j["d"][2]));
        h << "|d| " << number(d_mm, "%.1f") << " mm, " << j.value("iterations", 0) << " it"
          << (j.value("converged", false) ? "" : " (not converged)") << "<br>sign reversals ";
        if (const auto r = reversals(j))
          h << bold(*r == *fewest, std::to_string(*r)) << " ("
            << number(100.0 * j.value("gaussian_sign_reversal_fraction", 0.0)) << " %)"
            << band_reversals(j["curvature"], scale);
        else
          h << "not measured (no interior vertex)";
        const double across = norm(j, "orthogonal", "rms");
        h << "<br>across d: " << bold(across == *least_across, "RMS " + number(across) + " mm") << ", max "
          << number(norm(j, "orthogonal", "max")) << " mm<br>along d: RMS "
          << number(norm(j, "along_d", "rms")) << " mm, max " << number(norm(j, "along_d", "max")) << " mm";
      } else if (c.present) {
        h << "its metrics file does not parse";
      }
      const fs::path dir = fs::path(o.out) / methods[k];
      for (const char* kind : {"displacement", "curvature"}) {
        const std::string png = std::string(stem) + "-" + kind + ".png";
        if (fs::exists(dir / png))
          h << "<img src=\"" << escape(methods[k] + "/" + png) << "\" alt=\"" << kind << "\">";
      }
      h << "</td>";
    }
    h << "</tr>\n";
  }
  h << "</table></body></html>\n";
  const fs::path page = fs::path(o.out) / "compare.html";
  try {
    deform::write_file_atomically(page, h.str());
  } catch (const std::exception& e) {
    throw CommandError(page.string() + ": cannot write the comparison: " + e.what());
  }
  std::printf("pushpull replay: comparison %s\n", page.c_str());
  if (!failed.empty())
    throw CommandError("--compare: the " + failed + " replay failed (its output above says why)");
}

}  // namespace pushpull::app
