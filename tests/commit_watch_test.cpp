// app/commit_watch: the commits the deformation service publishes reach the loop in order, and a commit
// error published for a request the loop committed is a failed commit, also when it arrives before the loop
// says so; a preview's error is not.
#include "commit_watch.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace {

using pushpull::app::CommitWatch;
using pushpull::deform::Snapshot;

std::shared_ptr<const Snapshot> snapshot(Snapshot::Kind kind, std::uint64_t request,
                                         const std::string& error = "", bool failed_commit = false) {
  auto s = std::make_shared<Snapshot>();
  s->kind = kind;
  s->request = request;
  s->error = error;
  s->failed_commit = failed_commit;
  auto rest = std::make_shared<pushpull::deform::Mesh>();
  rest->V = Eigen::MatrixXd::Zero(3, 3);
  rest->F = Eigen::MatrixXi(1, 3);
  rest->F << 0, 1, 2;
  s->rest = rest;
  s->positions = std::shared_ptr<const Eigen::MatrixXd>(rest, &rest->V);
  return s;
}

TEST(CommitWatch, AnErrorForACommittedRequestIsAFailedCommitOthersAreNot) {
  CommitWatch watch;
  const auto publish = watch.callback();
  watch.expect_commit(7);
  publish(snapshot(Snapshot::Kind::Error, 5, "a preview failed"));  // not a commit: the readout shows it
  publish(snapshot(Snapshot::Kind::Error, 7, "the energy went negative", true));
  const auto failed = watch.take_failed();
  ASSERT_EQ(failed.size(), 1u);
  EXPECT_EQ(failed[0].request, 7u);
  EXPECT_EQ(failed[0].error, "the energy went negative");
  EXPECT_TRUE(watch.take().empty());
  EXPECT_TRUE(watch.take_failed().empty());
}

TEST(CommitWatch, AnErrorPublishedBeforeTheLoopSaysItCommittedStillCounts) {
  CommitWatch watch;
  const auto publish = watch.callback();
  publish(snapshot(Snapshot::Kind::Error, 9, "stale", true));
  watch.expect_commit(9);
  const auto failed = watch.take_failed();
  ASSERT_EQ(failed.size(), 1u);
  EXPECT_EQ(failed[0].error, "stale");
}

TEST(CommitWatch, ASuccessfulCommitIsTakenAndNotFailed) {
  CommitWatch watch;
  const auto publish = watch.callback();
  watch.expect_commit(3);
  publish(snapshot(Snapshot::Kind::Committed, 3));
  publish(snapshot(Snapshot::Kind::Error, 3, "a later error of the same request is not this commit's", true));
  const auto commits = watch.take();
  ASSERT_EQ(commits.size(), 1u);
  EXPECT_EQ(commits[0].index, 1u);
  EXPECT_TRUE(watch.take_failed().empty());
}

// The last preview of a drag failed (arap-s's energy check, from where a warm start began) and the loop then
// committed that request: the commit solves it again, cold, and may well succeed. The preview's error, before
// or after the loop says it committed, is not the commit's failure; the commit is taken when it comes.
TEST(CommitWatch, APreviewErrorOfTheCommittedRequestIsNotAFailedCommit) {
  CommitWatch watch;
  const auto publish = watch.callback();
  publish(snapshot(Snapshot::Kind::Error, 4, "the preview's energy went negative"));
  watch.expect_commit(4);
  publish(snapshot(Snapshot::Kind::Error, 4, "a preview still running when the commit came"));
  EXPECT_TRUE(watch.take_failed().empty());
  publish(snapshot(Snapshot::Kind::Committed, 4));
  EXPECT_EQ(watch.take().size(), 1u);
  EXPECT_TRUE(watch.take_failed().empty());
}

}  // namespace
