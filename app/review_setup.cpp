#include "review_setup.hpp"

#include "commands.hpp"
#include "model_output.hpp"
#include "output_guard.hpp"
#include "up_axis_note.hpp"

#include "pushpull/assets/write.hpp"
#include "pushpull/deform/file_output.hpp"
#include "pushpull/deform/mesh_io.hpp"

#include <cctype>
#include <cstdio>
#include <filesystem>

namespace pushpull::app {
namespace {

namespace fs = std::filesystem;

Eigen::Vector3d vec3(const std::vector<double>& v) { return {v.at(0), v.at(1), v.at(2)}; }
nlohmann::json to_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

std::string lower_extension(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

}  // namespace

ReviewSetup prepare_review(const ReviewCommandOptions& o) {
  if (!fs::exists(o.model)) throw CommandError(o.model + ": model file does not exist");
  std::error_code ec;
  if (!o.out.empty() && fs::is_directory(o.out, ec))
    throw CommandError(o.out + ": --out is a folder; name the file to write");
  if (!o.out.empty() && !deform::mesh_format_from_path(o.out) && lower_extension(o.out) != ".glb")
    throw CommandError(o.out + ": unsupported output format (expected .glb, .off, .obj or .ply)");
  // The review's outputs, checked before the session (a review is not repeated for a bad path): none may be
  // a folder or read-only, and no two may name one file (a recording written over by the event log, or the
  // model by either, is lost). Missing folders are made, as --record's default one is.
  {
    const std::pair<const char*, const std::string*> outputs[] = {
        {"--out", &o.out}, {"--record", &o.record}, {"--events", &o.events}};
    for (const auto& [option, path] : outputs) {
      if (path->empty()) continue;
      // --out is written atomically; the recording and the log line by line into the file itself.
      const std::string problem = deform::output_path_problem(
          *path, deform::MissingFolder::WillBeMade,
          path == &o.out ? deform::OutputWrite::Atomic : deform::OutputWrite::InPlace);
      if (!problem.empty()) throw CommandError(*path + ": " + option + " " + problem);
    }
    for (std::size_t a = 0; a < 3; ++a)
      for (std::size_t b = a + 1; b < 3; ++b)
        if (!outputs[a].second->empty() && !outputs[b].second->empty() &&
            deform::same_output_file(*outputs[a].second, *outputs[b].second))
          throw UsageError(*outputs[a].second + ": " + outputs[a].first + " and " + outputs[b].first +
                           " name the same file");
  }
  ReviewSetup s;
  try {
    s.model = assets::load_model(o.model);
  } catch (const std::exception& e) {
    throw CommandError(e.what());
  }
  if (!o.quiet)
    for (const std::string& w : assets::warnings_naming_the_file(s.model))
      std::fprintf(stderr, "pushpull review: warning: %s\n", w.c_str());
  const std::vector<InputFile> inputs = model_inputs(s.model.source_files);
  for (const auto& [option, path] :
       {std::pair{"--out", &o.out}, std::pair{"--record", &o.record}, std::pair{"--events", &o.events}})
    refuse_output_over_inputs(option, *path, inputs);
  if (!o.out.empty()) {  // found out now, not after the session (its folder is made as --record's is)
    const fs::path folder = fs::path(o.out).parent_path();
    if (!folder.empty() && !fs::is_directory(folder, ec)) {
      fs::create_directories(folder, ec);
      std::error_code made;
      if (ec || !fs::is_directory(folder, made))
        throw CommandError(o.out + ": cannot make its folder " + folder.string() +
                           (ec ? " (" + ec.message() + ")" : std::string()));
    }
  }
  s.life = LifeSize(o.life_size, s.model.bounds, o.model);
  {
    // The size the reviewer will see. A model far from a walk-around size is most often one in other units
    // (a 7 cm toy car in metres, a car in millimetres): say how to make it life size.
    const Eigen::Vector3d size = s.model.bounds.sizes() * s.life.scale();
    const double longest = size.maxCoeff();
    if (!o.quiet)
      std::printf(longest < 1e6 ? "pushpull review: the model is %.2f x %.2f x %.2f m at this scale\n"
                                : "pushpull review: the model is %.3g x %.3g x %.3g m at this scale\n",
                  size.x(), size.y(), size.z());
    if (const auto hint = size_hint(longest))
      std::fprintf(stderr, "pushpull review: note: %s\n", hint->c_str());
  }
  if (!o.quiet && !o.up_given)
    if (const auto note = plain_mesh_up_note(o.model, s.model.bounds.sizes() * s.life.scale()))
      std::fprintf(stderr, "pushpull review: note: %s\n", note->c_str());
  s.rest = std::make_shared<const deform::Mesh>(s.model.deform_mesh);
  PlacementOptions placement;
  placement.up_model = vec3(o.up);
  placement.front_model = vec3(o.front);
  placement.scale = s.life.scale();
  placement.distance_m = o.distance_m;
  try {
    s.placement = place_on_stage(s.rest->V, placement);
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("--up/--front: ") + e.what());
  }
  s.interaction.handle_radius = s.life.to_file_units(o.handle_radius_m);
  s.interaction.roi_radius = s.life.to_file_units(o.roi_radius_m);
  s.interaction.scale = s.life.scale();
  try {
    s.interaction.solver.method = deform::parse_method(o.method);
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("--method: ") + e.what());
  }
  s.interaction.solver.mu = o.mu;
  if (o.smooth_start_min_free) s.interaction.solver.smooth_start_min_free = *o.smooth_start_min_free;
  if (o.coarse_start_min_free) s.interaction.solver.coarse_start_min_free = *o.coarse_start_min_free;
  s.colour = parse_colour(o.colour).value_or(ReviewColour::Displacement);
  return s;
}

void write_review_model(const std::string& path, const assets::Model& model, const Eigen::MatrixXd& V,
                        bool say_warnings) {
  for (const std::string& w : write_deformed_model(path, model.source_path, model.deform_mesh, &model, V))
    if (say_warnings) std::printf("  warning: %s\n", w.c_str());
}

EventLog::EventLog(const std::string& path, bool print) : print_(print) {
  if (path.empty()) return;
  file_.open(path);
  if (!file_) throw CommandError(path + ": cannot write the event log");
}

void EventLog::write(const nlohmann::json& line) {
  // (replace: a path that is not UTF-8, from the command line, is written with U+FFFD, not thrown on)
  if (file_.is_open())
    file_ << line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << '\n' << std::flush;
}

void EventLog::write_start(const ReviewCommandOptions& o, const ReviewSetup& s, const std::string& runtime) {
  nlohmann::json header{{"event", "start"},
                        {"model", o.model},
                        {"scale", s.life.scale()},
                        {"method", o.method},
                        {"mu", o.mu},
                        {"handle_radius", s.interaction.handle_radius},
                        {"roi_radius", s.interaction.roi_radius},
                        {"runtime", runtime}};
  std::vector<double> T;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) T.push_back(s.placement.T_stage_model(r, c));
  header["T_stage_model"] = T;  // row-major 4x4
  write(header);
}

void EventLog::write_method(deform::Method method) {
  const std::string name(deform::method_name(method));
  write({{"event", "method"}, {"method", name}});
  if (print_) std::printf("pushpull review: method %s for the next push/pulls\n", name.c_str());
}

void EventLog::write_colour(ReviewColour colour) {
  write({{"event", "colour"}, {"colour", colour_name(colour)}});
  if (print_) std::printf("pushpull review: colour map %s\n", colour_name(colour));
}

void EventLog::write_interaction(const InteractionEvent& e, const LifeSize& life) {
  static const char* names[] = {"press", "commit", "cancel"};
  nlohmann::json line{{"event", names[int(e.kind)]},
                      {"hand", e.hand == 0 ? "left" : "right"},
                      {"face", e.face},
                      {"p0", to_json(e.p0)},
                      {"d", to_json(e.d)},
                      {"method", std::string(deform::method_name(e.method))}};
  if (e.kind == InteractionEvent::Kind::Committed) line["request"] = e.request;
  write(line);
  if (print_)
    std::printf("pushpull review: %s at p0 = (%.4f, %.4f, %.4f) m (model axes, life size), |d| = %.1f mm\n",
                names[int(e.kind)], life.scale() * e.p0.x(), life.scale() * e.p0.y(), life.scale() * e.p0.z(),
                life.to_mm(e.d.norm()));
}

}  // namespace pushpull::app
