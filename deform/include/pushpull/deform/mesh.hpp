// pushpull::deform::Mesh: the triangle surface every deformation works on.
//
// Units: whatever the model uses (glTF models are in metres). Frame: model space.
// Shapes: V is #V by 3 (double, one vertex per row); F is #F by 3 (int, 0-based vertex indices,
// counter-clockwise seen from outside).
// Ownership: a plain value type. Thread-safety: none of its own; share it as
// std::shared_ptr<const Mesh> across threads.
#pragma once

#include <Eigen/Core>

namespace pushpull::deform {

struct Mesh {
  Eigen::MatrixXd V;  // #V by 3 vertex positions
  Eigen::MatrixXi F;  // #F by 3 triangle vertex indices, 0-based

  [[nodiscard]] Eigen::Index vertex_count() const { return V.rows(); }
  [[nodiscard]] Eigen::Index face_count() const { return F.rows(); }
};

}  // namespace pushpull::deform
