// A point printed for the user to copy back into an option (--handle-at X Y Z): life-size metres to the
// micrometre, in fixed notation, so a model far from its file's origin (1e6 m in site coordinates) keeps the
// digits that say where on it the point is ("%.6g" printed 1e+06).
// Thread-safety: pure function.
#pragma once

#include <Eigen/Core>

#include <string>

namespace pushpull::app {

// "X Y Z": each coordinate rounded to the micrometre, trailing zeros dropped, no negative zero; beyond 1e12 m
// (no micrometres left in a double) in %.6g.
std::string point_in_metres_text(const Eigen::Vector3d& metres);

}  // namespace pushpull::app
