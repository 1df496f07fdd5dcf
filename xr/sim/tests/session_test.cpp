// The session state machine, its events, and frame calls in the wrong state, through the loader.
#include "sim_fixture.hpp"

#include <gtest/gtest.h>

#include <thread>

using namespace sim_test;

namespace {

class SessionTest : public ::testing::Test {
 protected:
  void SetUp() override { use_simulated_runtime(); }
};

XrSessionBeginInfo stereo() {
  XrSessionBeginInfo bi{XR_TYPE_SESSION_BEGIN_INFO};
  bi.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  return bi;
}

TEST_F(SessionTest, StateMachineFromIdleToExiting) {
  Sim sim;
  sim.create_session();
  EXPECT_EQ(sim.poll_states(), (std::vector<XrSessionState>{XR_SESSION_STATE_IDLE, XR_SESSION_STATE_READY}));
  const XrSessionBeginInfo bi = stereo();
  ASSERT_EQ(xrBeginSession(sim.session, &bi), XR_SUCCESS);
  sim.frame();
  EXPECT_EQ(sim.poll_states(),
            (std::vector<XrSessionState>{XR_SESSION_STATE_SYNCHRONIZED, XR_SESSION_STATE_VISIBLE,
                                         XR_SESSION_STATE_FOCUSED}));
  ASSERT_EQ(xrRequestExitSession(sim.session), XR_SUCCESS);
  EXPECT_EQ(sim.poll_states(),
            (std::vector<XrSessionState>{XR_SESSION_STATE_VISIBLE, XR_SESSION_STATE_SYNCHRONIZED,
                                         XR_SESSION_STATE_STOPPING}));
  ASSERT_EQ(xrEndSession(sim.session), XR_SUCCESS);
  EXPECT_EQ(sim.poll_states(),
            (std::vector<XrSessionState>{XR_SESSION_STATE_IDLE, XR_SESSION_STATE_EXITING}));
  EXPECT_EQ(xrDestroySession(sim.session), XR_SUCCESS);
  EXPECT_EQ(xrDestroySession(sim.session), XR_ERROR_HANDLE_INVALID);
  sim.session = XR_NULL_HANDLE;
}

TEST_F(SessionTest, CallsInTheWrongStateFail) {
  Sim sim;
  sim.create_session();
  XrFrameState fs{XR_TYPE_FRAME_STATE};
  EXPECT_EQ(xrWaitFrame(sim.session, nullptr, &fs), XR_ERROR_SESSION_NOT_RUNNING);
  EXPECT_EQ(xrBeginFrame(sim.session, nullptr), XR_ERROR_SESSION_NOT_RUNNING);
  EXPECT_EQ(xrEndSession(sim.session), XR_ERROR_SESSION_NOT_RUNNING);
  EXPECT_EQ(xrRequestExitSession(sim.session), XR_ERROR_SESSION_NOT_RUNNING);
  XrSessionBeginInfo mono = stereo();
  mono.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_MONO;
  EXPECT_EQ(xrBeginSession(sim.session, &mono), XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED);
  const XrSessionBeginInfo bi = stereo();
  ASSERT_EQ(xrBeginSession(sim.session, &bi), XR_SUCCESS);
  EXPECT_EQ(xrBeginSession(sim.session, &bi), XR_ERROR_SESSION_RUNNING);
  EXPECT_EQ(xrEndSession(sim.session), XR_ERROR_SESSION_NOT_STOPPING);
  // Frame call order.
  EXPECT_EQ(xrBeginFrame(sim.session, nullptr), XR_ERROR_CALL_ORDER_INVALID);
  XrFrameEndInfo ei{XR_TYPE_FRAME_END_INFO};
  ei.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  ei.displayTime = 1;
  EXPECT_EQ(xrEndFrame(sim.session, &ei), XR_ERROR_CALL_ORDER_INVALID);
  ASSERT_EQ(xrWaitFrame(sim.session, nullptr, &fs), XR_SUCCESS);
  ASSERT_EQ(xrBeginFrame(sim.session, nullptr), XR_SUCCESS);
  ASSERT_EQ(xrWaitFrame(sim.session, nullptr, &fs), XR_SUCCESS);
  EXPECT_EQ(xrBeginFrame(sim.session, nullptr), XR_FRAME_DISCARDED);  // the previous frame never ended
  ei.displayTime = 0;
  EXPECT_EQ(xrEndFrame(sim.session, &ei), XR_ERROR_TIME_INVALID);
  ei.displayTime = fs.predictedDisplayTime;
  ei.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_ADDITIVE;
  EXPECT_EQ(xrEndFrame(sim.session, &ei), XR_ERROR_ENVIRONMENT_BLEND_MODE_UNSUPPORTED);
  ei.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  EXPECT_EQ(xrEndFrame(sim.session, &ei), XR_SUCCESS);
}

TEST_F(SessionTest, RealTimeFramesArePacedAtTheConfiguredRate) {
  setenv("PUSHPULL_XR_SIM_RATE", "50", 1);
  Sim sim;
  sim.create_session();
  sim.begin_session();
  const auto start = std::chrono::steady_clock::now();
  XrTime first = sim.frame(), last = first;
  for (int i = 0; i < 10; ++i) last = sim.frame();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Display times stay on the 50 Hz vsync grid (a late frame skips vsyncs, it never runs off the grid).
  EXPECT_EQ((last - first) % 20000000, 0);
  EXPECT_GE(last - first, 10 * 20000000);
  EXPECT_GT(seconds, 0.15);  // paced, not free-running
}

TEST_F(SessionTest, ScriptedClockIsVirtualAndScriptedExitAndLossArrive) {
  setenv("PUSHPULL_XR_SIM_INPUT",
         write_temp_file("exit.jsonl", "{\"t\": 0.1, \"event\": \"exit\"}\n").c_str(), 1);
  setenv("PUSHPULL_XR_SIM_RATE", "10", 1);
  Sim sim;
  sim.create_session();
  sim.begin_session();
  const auto start = std::chrono::steady_clock::now();
  const XrTime t0 = sim.frame();
  const XrTime t1 = sim.frame();
  EXPECT_EQ(t1 - t0, 100000000);  // 1/10 s per frame on the virtual clock
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.09);
  const auto states = sim.poll_states();
  ASSERT_FALSE(states.empty());
  EXPECT_EQ(states.back(), XR_SESSION_STATE_STOPPING);
  ASSERT_EQ(xrEndSession(sim.session), XR_SUCCESS);
  EXPECT_EQ(sim.poll_states().back(), XR_SESSION_STATE_EXITING);
}

TEST_F(SessionTest, ScriptedLossGivesLossPending) {
  setenv("PUSHPULL_XR_SIM_INPUT",
         write_temp_file("loss.jsonl", "{\"t\": 0.0, \"event\": \"loss\"}\n").c_str(), 1);
  Sim sim;
  sim.create_session();
  sim.begin_session();
  XrFrameState fs{XR_TYPE_FRAME_STATE};
  EXPECT_EQ(xrWaitFrame(sim.session, nullptr, &fs), XR_SESSION_LOSS_PENDING);
  EXPECT_EQ(sim.poll_states().back(), XR_SESSION_STATE_LOSS_PENDING);
  EXPECT_EQ(xrDestroySession(sim.session), XR_SUCCESS);
}

TEST_F(SessionTest, WaitFrameOnAnotherThreadBlocksUntilBeginFrame) {
  Sim sim;
  sim.create_session();
  sim.begin_session();
  XrFrameState fs{XR_TYPE_FRAME_STATE};
  ASSERT_EQ(xrWaitFrame(sim.session, nullptr, &fs), XR_SUCCESS);
  std::atomic<bool> second_wait_done{false};
  std::thread waiter([&] {
    XrFrameState fs2{XR_TYPE_FRAME_STATE};
    EXPECT_EQ(xrWaitFrame(sim.session, nullptr, &fs2), XR_SUCCESS);
    second_wait_done = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_FALSE(second_wait_done.load());  // blocked: frame 1 was waited but not begun
  ASSERT_EQ(xrBeginFrame(sim.session, nullptr), XR_SUCCESS);
  waiter.join();
  EXPECT_TRUE(second_wait_done.load());
  XrFrameEndInfo ei{XR_TYPE_FRAME_END_INFO};
  ei.displayTime = fs.predictedDisplayTime;
  ei.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  EXPECT_EQ(xrEndFrame(sim.session, &ei), XR_SUCCESS);
  EXPECT_EQ(xrBeginFrame(sim.session, nullptr), XR_SUCCESS);
  EXPECT_EQ(xrEndFrame(sim.session, &ei), XR_SUCCESS);
}

}  // namespace
