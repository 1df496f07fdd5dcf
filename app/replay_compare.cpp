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
#include <sstream>

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
  h << "<p>Each column replays the session's push/pulls with one method (the paper's criteria, section 5: "
       "the "
       "displacement across d, which ASAN keeps small by carrying the sections across d unchanged, and the "
       "Gaussian curvature sign reversals, a bonnet turning saddle: smaller is the shape better kept; the "
       "displacement along d is what the pull asked for). Each method goes on from its own results: a "
       "push/pull after the first starts from that method's shape, so later rows compare the methods on "
       "surfaces that may already differ (each report's <i>region</i> row gives its size).</p>\n<table>\n"
       "<tr><th>push/pull</th>";
  for (const std::string& m : methods)
    h << "<th>" << escape(m) << " (<a href=\"" << escape(m) << "/report.html\">report</a>)</th>";
  h << "</tr>\n";
  for (int i = 1;; ++i) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "commit-%02d", i);
    bool any = false;
    std::ostringstream row;
    row << "<tr><th>Push/pull " << i << "</th>";
    for (const std::string& m : methods) {
      const fs::path dir = fs::path(o.out) / m;
      std::ifstream in(dir / (std::string(stem) + ".metrics.json"));
      row << "<td>";
      if (in) {
        any = true;
        const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
        if (!j.is_discarded()) {
          const double scale = j.value("life_size_scale", 1.0);
          const auto& d = j["d"];
          const double d_mm = 1000.0 * scale *
                              std::sqrt(double(d[0]) * double(d[0]) + double(d[1]) * double(d[1]) +
                                        double(d[2]) * double(d[2]));
          row << "|d| " << number(d_mm, "%.1f") << " mm, " << j.value("iterations", 0) << " it"
              << (j.value("converged", false) ? "" : " (not converged)") << "<br>sign reversals ";
          if (j["curvature"].value("evaluated_vertices", 0) == 0)
            row << "not measured (no interior vertex)";
          else
            row << j["curvature"].value("sign_reversals", 0) << " ("
                << number(100.0 * j.value("gaussian_sign_reversal_fraction", 0.0)) << " %)"
                << band_reversals(j["curvature"], scale);
          const auto norm = [&](const char* part, const char* which) {
            if (!j.contains("norms") || !j["norms"].is_object()) return 0.0;
            const auto& norms = j["norms"];
            return norms.contains(part) && norms[part].is_object()
                       ? 1000.0 * scale * norms[part].value(which, 0.0)
                       : 0.0;
          };
          row << "<br>across d: RMS " << number(norm("orthogonal", "rms")) << " mm, max "
              << number(norm("orthogonal", "max")) << " mm<br>along d: RMS " << number(norm("along_d", "rms"))
              << " mm, max " << number(norm("along_d", "max")) << " mm";
        }
        for (const char* kind : {"displacement", "curvature"}) {
          const std::string png = std::string(stem) + "-" + kind + ".png";
          if (fs::exists(dir / png)) row << "<img src=\"" << escape(m + "/" + png) << "\" alt=\"" << kind << "\">";
        }
      }
      row << "</td>";
    }
    row << "</tr>\n";
    if (!any) break;
    h << row.str();
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
