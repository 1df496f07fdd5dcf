// Private: one step of closest_rotation (rotation.hpp) on a batch of clusters at once, written lane by lane
// so that the compiler vectorises it (SSE2, or AVX2 / AVX-512 where the CPU has them, chosen at run time).
// Every lane does exactly the scalar arithmetic of the others in the same order, without fused multiply-add,
// so the results are bit-identical whichever instruction set runs (a replay on another x86-64 machine
// reproduces the same hashes).
#pragma once

#include <cstdint>

namespace pushpull::deform::detail {

inline constexpr int kRotationLanes = 8;

// Structure of arrays for kRotationLanes clusters: a = the 3x3 covariances (row-major: a[3 i + j][lane] =
// A(i, j)); q = the warm-start quaternions (x, y, z, w); r = the rotations written by the step (row-major).
// Unused lanes must hold finite values (e.g. A = I, q = identity); their results are to be ignored.
struct RotationLanes {
  alignas(64) double a[9][kRotationLanes];
  alignas(64) double q[4][kRotationLanes];
  alignas(64) double r[9][kRotationLanes];
};

// One Newton (or gradient) step of closest_rotation from each lane's q, with the same rules: the step is
// taken where A is finite and nonzero and the gradient is not ~0; q is updated and r is its rotation. A lane
// whose A has a NaN or infinite entry, or is zero, keeps its q (finished, r = R(q)). Pure and re-entrant:
// it reads and writes `lanes` only.
// Returns a bit mask of the lanes that are finished (as closest_rotation would have returned after this
// step: a Newton step shorter than accept_step, already at the maximum, or A ~ 0). The other lanes must go
// on with closest_rotation from their updated q (more steps, or the SVD at a saddle).
[[nodiscard]] std::uint32_t closest_rotation_step(RotationLanes& lanes, double accept_step);

}  // namespace pushpull::deform::detail
