// A text label standing in the review's stage (the readout by the hand, the menu panel): lines of text on a
// dark panel, drawn on top of the model so it is never hidden, facing a viewer. Owns one streamed renderer mesh
// of fixed capacity (renderer/text_label.hpp); changing the text streams new positions, nothing is allocated on
// the GPU per frame.
// Frames: stage space, metres. Ownership: borrows the Renderer (outlives this). Thread-safety: the renderer's
// thread only.
#pragma once

#include "pushpull/renderer/renderer.hpp"

#include <Eigen/Core>
#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

namespace pushpull::app {

class WorldLabel {
 public:
  // line_height: metres between baselines; max_quads: glyph capacity (about 4 per character).
  WorldLabel(renderer::Renderer& renderer, float line_height, unsigned max_quads);

  // The text (highlight_line: the line with the accent bar, -1 none). Streams positions only when it changed.
  void set_text(const std::vector<std::string>& lines, int highlight_line = -1);
  // Places the panel: its bottom centre at `anchor`, facing `viewer`, its text lines horizontal, `scale` times
  // its line height (a desktop camera far away: larger, to stay readable).
  void place(const Eigen::Vector3d& anchor, const Eigen::Vector3d& viewer, double scale = 1.0);
  // Places the panel parallel to a camera's image plane: its bottom centre at `anchor`, its text along the
  // camera's `right`, its lines stacked along the camera's `up` (unit, orthogonal; stage frame), `scale`
  // times its line height. A window's readout: upright on the screen however the camera looks (straight down
  // too).
  void place_on_image_plane(const Eigen::Vector3d& anchor, const Eigen::Vector3d& right,
                            const Eigen::Vector3d& up, double scale);
  // Pins the panel to the top-left corner of `view`'s image (a window's heads-up display): parallel to the
  // image plane, inside the view's depth range, a line `line_fraction` of the image height tall, half a line
  // from the edges. Call per frame with the frame's view.
  void place_top_left(const renderer::View& view, double line_fraction);
  void hide() { visible_ = false; }
  [[nodiscard]] bool visible() const { return visible_; }
  [[nodiscard]] const std::vector<std::string>& lines() const { return lines_; }
  [[nodiscard]] float height() const { return height_; }  // of the panel with the current text (metres)
  [[nodiscard]] float width() const { return width_; }    // likewise
  [[nodiscard]] const glm::mat4& transform() const { return T_stage_label_; }  // where place*() put it
  // The draw while visible (on top, its own unlit materials).
  [[nodiscard]] std::optional<renderer::Draw> draw() const;

 private:
  renderer::Renderer& renderer_;
  float line_height_;
  unsigned max_quads_;
  renderer::MeshId mesh_ = 0;
  std::vector<std::string> lines_;
  int highlight_ = -1;
  bool has_text_ = false;
  bool visible_ = false;
  glm::mat4 T_stage_label_{1.0f};
  float height_ = 0.0f;
  float width_ = 0.0f;
};

}  // namespace pushpull::app
