// app/history_steps: an undo or redo with nothing to step to is not sent (the loops say so instead); the
// edits as the HUD and the title count them.
#include "history_steps.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace pushpull::app {
namespace {

// A 9 x 9 sheet on [0, 1]^2 whose centre vertex is pulled up by 0.1 (border fixed).
std::shared_ptr<const deform::Mesh> sheet() {
  auto mesh = std::make_shared<deform::Mesh>();
  constexpr int n = 9;
  mesh->V.resize(n * n, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) mesh->V.row(j * n + i) << i / double(n - 1), j / double(n - 1), 0.0;
  mesh->F.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i;
      mesh->F.row(f++) << a, a + 1, a + n + 1;
      mesh->F.row(f++) << a, a + n + 1, a + n;
    }
  return mesh;
}

deform::Request pull() {
  deform::Request r;
  r.handle = deform::VertexHandle{{40}};
  for (int v = 0; v < 81; ++v)
    if (v % 9 == 0 || v % 9 == 8 || v < 9 || v >= 72) r.region.fixed.push_back(v);
  r.d = Eigen::Vector3d(0.0, 0.0, 0.1);
  return r;
}

TEST(HistorySteps, NothingToStepToIsNotSentAndTheEditsAreCounted) {
  const auto mesh = sheet();
  deform::Service service(mesh);
  EXPECT_EQ(edit_counts_text(edit_counts(service)), "no edits");
  EXPECT_FALSE(request_history_step(service, HistoryStep::Undo));
  EXPECT_FALSE(request_history_step(service, HistoryStep::Redo));
  (void)service.submit(pull());
  (void)service.commit();
  (void)service.wait_idle();
  EXPECT_EQ(edit_counts_text(edit_counts(service)), "1 edit");
  EXPECT_FALSE(request_history_step(service, HistoryStep::Redo));
  EXPECT_TRUE(request_history_step(service, HistoryStep::Undo));
  (void)service.wait_idle();
  EXPECT_EQ(edit_counts_text(edit_counts(service)), "1 edit, 1 undone");
  EXPECT_FALSE(request_history_step(service, HistoryStep::Undo));
  EXPECT_TRUE(request_history_step(service, HistoryStep::Redo));
  (void)service.wait_idle();
  EXPECT_EQ(service.history_position(), 1u);
  EXPECT_STREQ(nothing_to(HistoryStep::Undo), "nothing to undo");
  EXPECT_STREQ(nothing_to(HistoryStep::Redo), "nothing to redo");
}

TEST(HistorySteps, TextsOfTheCounts) {
  EXPECT_EQ(edit_counts_text({0, 0}), "no edits");
  EXPECT_EQ(edit_counts_text({3, 0}), "3 edits");
  EXPECT_EQ(edit_counts_text({3, 2}), "3 edits, 2 undone");
}

}  // namespace
}  // namespace pushpull::app
