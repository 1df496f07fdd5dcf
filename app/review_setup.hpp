// What `pushpull review` prepares before any window or headset: the model, its life size, the stage
// placement, the interaction options, the start colour map; and what it writes at the end (the committed
// model, the event log). Shared by the headset loop (review_loop.cpp) and desktop mode (desktop_loop.cpp).
// Thread-safety: plain values; EventLog is for one thread.
#pragma once

#include "life_size.hpp"
#include "review_interaction.hpp"
#include "review_loop.hpp"
#include "review_scene.hpp"
#include "stage_placement.hpp"

#include "pushpull/assets/model.hpp"

#include <nlohmann/json.hpp>

#include <fstream>
#include <memory>
#include <string>

namespace pushpull::app {

struct ReviewSetup {
  assets::Model model;
  LifeSize life;
  std::shared_ptr<const deform::Mesh> rest;  // the welded deform mesh (model space, file units)
  StagePlacement placement;
  InteractionOptions interaction;
  ReviewColour colour = ReviewColour::Displacement;
};

// Loads and checks everything the options name; throws CommandError naming the file or option.
ReviewSetup prepare_review(const ReviewCommandOptions& options);

// The committed positions V (#V by 3) of setup.model as .glb (the scene with moved vertices) or OFF/OBJ/PLY
// (the welded mesh); what the file leaves out is printed as warnings when say_warnings. Throws CommandError
// naming the file.
void write_review_model(const std::string& path, const assets::Model& model, const Eigen::MatrixXd& V,
                        bool say_warnings = true);

// JSON Lines event log (--events); writes nothing when the path is empty. Each line is flushed.
class EventLog {
 public:
  // print: also print press / commit / cancel lines on stdout.
  EventLog(const std::string& path, bool print);
  void write(const nlohmann::json& line);
  // The start line: model, scale, method, radii, T_stage_model (row-major 4x4), where it runs.
  void write_start(const ReviewCommandOptions& options, const ReviewSetup& setup, const std::string& runtime);
  // press / commit / cancel, with p0, face and d in model units; also printed with |d| in life-size mm.
  void write_interaction(const InteractionEvent& event, const LifeSize& life);
  // {"event": "method", "method": NAME}: the method of the push/pulls from here on; printed ("method NAME for
  // the next push/pulls") unless quiet.
  void write_method(deform::Method method);
  // {"event": "colour", "colour": NAME}: the colour map shown from here on; printed ("colour map NAME")
  // unless quiet.
  void write_colour(ReviewColour colour);

 private:
  std::ofstream file_;
  bool print_ = true;
};

}  // namespace pushpull::app
