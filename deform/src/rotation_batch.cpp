#include "rotation_batch.hpp"

#include <cfloat>
#include <cmath>

namespace pushpull::deform::detail {
namespace {

// R(q) for a unit quaternion, row-major.
inline void rotation_of(double x, double y, double z, double w, double* r) {
  const double tx = 2.0 * x, ty = 2.0 * y, tz = 2.0 * z;
  const double twx = tx * w, twy = ty * w, twz = tz * w;
  const double txx = tx * x, txy = ty * x, txz = tz * x;
  const double tyy = ty * y, tyz = tz * y, tzz = tz * z;
  r[0] = 1.0 - (tyy + tzz);
  r[1] = txy - twz;
  r[2] = txz + twy;
  r[3] = txy + twz;
  r[4] = 1.0 - (txx + tzz);
  r[5] = tyz - twx;
  r[6] = txz - twy;
  r[7] = tyz + twx;
  r[8] = 1.0 - (txx + tyy);
}

}  // namespace

// The clones differ only in vector width; no FMA is enabled in any of them (see the header). Not under the
// sanitizers: their run-time is not set up yet when the loader calls the clones' resolver (a crash at start).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__) && \
    !defined(__SANITIZE_THREAD__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
std::uint32_t
closest_rotation_step(RotationLanes& lanes, double accept_step) {
  const double accept2 = accept_step * accept_step;
  int finished[kRotationLanes];
  for (int l = 0; l < kRotationLanes; ++l) {
    // Branch-free throughout (selects, & on conditions), so that the loop vectorises.
    double m = 0.0, total = 0.0;
    for (int k = 0; k < 9; ++k) {
      const double magnitude = std::fabs(lanes.a[k][l]);
      m = magnitude > m ? magnitude : m;
      total += magnitude;
    }
    const bool valid = (m > 0.0) & (m <= DBL_MAX) & (total == total);  // false for a NaN or infinite entry
    const double inv = 1.0 / (valid ? m : 1.0);
    double b[9];
    for (int k = 0; k < 9; ++k) b[k] = lanes.a[k][l] * inv;
    const double qx = lanes.q[0][l], qy = lanes.q[1][l], qz = lanes.q[2][l], qw = lanes.q[3][l];
    double r[9];
    rotation_of(qx, qy, qz, qw, r);
    // S = R^T B.
    double s[9];
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) s[3 * i + j] = r[i] * b[j] + r[3 + i] * b[3 + j] + r[6 + i] * b[6 + j];
    }
    const double ax = s[7] - s[5], ay = s[2] - s[6], az = s[3] - s[1];
    const double t = s[0] + s[4] + s[8];
    const double h00 = t - s[0], h11 = t - s[4], h22 = t - s[8];
    const double h01 = -0.5 * (s[1] + s[3]), h02 = -0.5 * (s[2] + s[6]), h12 = -0.5 * (s[5] + s[7]);
    const double c00 = h11 * h22 - h12 * h12, c01 = h02 * h12 - h01 * h22, c02 = h01 * h12 - h02 * h11;
    const double det = h00 * c00 + h01 * c01 + h02 * c02;
    const double minor2 = h00 * h11 - h01 * h01;
    const bool basin = (h00 > 1e-9) & (minor2 > 1e-12) & (det > 1e-15);
    const double a2 = ax * ax + ay * ay + az * az;
    const bool stationary = a2 < 1e-28;
    const double c11 = h00 * h22 - h02 * h02, c12 = h02 * h01 - h00 * h12, c22 = minor2;
    const double inv_det = 1.0 / (basin ? det : 1.0);
    const double newton_x = (c00 * ax + c01 * ay + c02 * az) * inv_det;
    const double newton_y = (c01 * ax + c11 * ay + c12 * az) * inv_det;
    const double newton_z = (c02 * ax + c12 * ay + c22 * az) * inv_det;
    const double gradient = 1.0 / (std::fabs(t) + 1e-12);
    double wx = basin ? newton_x : ax * gradient;
    double wy = basin ? newton_y : ay * gradient;
    double wz = basin ? newton_z : az * gradient;
    const double w2 = wx * wx + wy * wy + wz * wz;
    const double trust = 1.0 / std::sqrt(w2 > 1.0 ? w2 : 1.0);  // one radian at most
    wx *= trust;
    wy *= trust;
    wz *= trust;
    // q <- q (1, w / 2), normalised.
    const double vx = 0.5 * wx, vy = 0.5 * wy, vz = 0.5 * wz;
    double nw = qw - (qx * vx + qy * vy + qz * vz);
    double nx = qw * vx + qx + (qy * vz - qz * vy);
    double ny = qw * vy + qy + (qz * vx - qx * vz);
    double nz = qw * vz + qz + (qx * vy - qy * vx);
    const double norm = 1.0 / std::sqrt(nx * nx + ny * ny + nz * nz + nw * nw);
    nx *= norm;
    ny *= norm;
    nz *= norm;
    nw *= norm;
    const bool step = valid & !stationary;
    lanes.q[0][l] = step ? nx : qx;
    lanes.q[1][l] = step ? ny : qy;
    lanes.q[2][l] = step ? nz : qz;
    lanes.q[3][l] = step ? nw : qw;
    double moved[9];
    rotation_of(nx, ny, nz, nw, moved);
    for (int k = 0; k < 9; ++k) lanes.r[k][l] = step ? moved[k] : r[k];
    finished[l] = (!valid) | (stationary & basin) | (step & basin & (w2 < accept2));
  }
  std::uint32_t mask = 0;
  for (int l = 0; l < kRotationLanes; ++l) mask |= static_cast<std::uint32_t>(finished[l] != 0) << l;
  return mask;
}

}  // namespace pushpull::deform::detail
