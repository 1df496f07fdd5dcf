// app/solver_state: while a drag waits for its first preview, the readouts do not show the previous
// push/pull's commit ("72 it converged" next to the new drag's |d|) as this drag's progress.
#include "solver_state.hpp"

#include <gtest/gtest.h>

#include <string>

namespace pushpull::app {
namespace {

deform::Snapshot snapshot(deform::Snapshot::Kind kind, int iteration, bool final, bool converged) {
  deform::Snapshot s;
  s.kind = kind;
  s.iteration = iteration;
  s.final = final;
  s.converged = converged;
  return s;
}

TEST(SolverState, BeforeTheDragsFirstPreviewItWaitsWithNoIterations) {
  using Kind = deform::Snapshot::Kind;
  for (const Kind kind : {Kind::Committed, Kind::Rest}) {  // the last commit, or an undo's state
    const deform::Snapshot s = snapshot(kind, 72, true, true);
    EXPECT_FALSE(is_drag_preview(s));
    EXPECT_EQ(std::string(solver_state(s)), "waiting");
    EXPECT_EQ(drag_iterations(s), 0);
  }
}

TEST(SolverState, APreviewSaysSolvingThenHowItEnded) {
  using Kind = deform::Snapshot::Kind;
  EXPECT_EQ(std::string(solver_state(snapshot(Kind::Preview, 3, false, false))), "solving");
  EXPECT_EQ(std::string(solver_state(snapshot(Kind::Preview, 40, true, true))), "converged");
  EXPECT_EQ(std::string(solver_state(snapshot(Kind::Preview, 1000, true, false))), "not converged");
  EXPECT_EQ(drag_iterations(snapshot(Kind::Preview, 40, true, true)), 40);
}

}  // namespace
}  // namespace pushpull::app
