// app/solver_cpus: `pushpull review --solver-cpus` lists, "auto" and "none", and the errors that name the
// problem.
#include "solver_cpus.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace pushpull::app {
namespace {

using Cpus = std::vector<int>;

// No SMT: every CPU a core of its own.
Cpus alone(int cpu) {
  return {cpu};
}

std::string error_of(const std::string& spec, const Cpus& allowed) {
  try {
    (void)split_cpus(spec, allowed, alone);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(SolverCpus, ListsAndRangesSplitTheAllowedCpus) {
  const Cpus allowed{0, 1, 2, 3, 4, 5, 6, 7};
  const auto a = split_cpus("3", allowed, alone);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->solver, (Cpus{3}));
  EXPECT_EQ(a->frames, (Cpus{0, 1, 2, 4, 5, 6, 7}));
  const auto b = split_cpus("6-7,2,2", allowed, alone);
  ASSERT_TRUE(b);
  EXPECT_EQ(b->solver, (Cpus{2, 6, 7}));
  EXPECT_EQ(b->frames, (Cpus{0, 1, 3, 4, 5}));
}

TEST(SolverCpus, AutoTakesTheLastCpuWhenThereAreTwo) {
  const auto two = split_cpus("auto", {0, 1}, alone);
  ASSERT_TRUE(two);
  EXPECT_EQ(two->solver, (Cpus{1}));
  EXPECT_EQ(two->frames, (Cpus{0}));
  const auto gaps = split_cpus("auto", {2, 5, 9}, alone);
  ASSERT_TRUE(gaps);
  EXPECT_EQ(gaps->solver, (Cpus{9}));
  EXPECT_EQ(gaps->frames, (Cpus{2, 5}));
  EXPECT_FALSE(split_cpus("auto", {0}, alone));  // one CPU: nothing to split
  EXPECT_FALSE(split_cpus("auto", {}, alone));
  EXPECT_FALSE(split_cpus("none", {0, 1}, alone));
}

TEST(SolverCpus, ErrorsNameTheProblem) {
  const Cpus allowed{0, 1};
  EXPECT_NE(error_of("0-1", allowed).find("leaves no CPU for the frames (this process has 0-1)"),
            std::string::npos);
  EXPECT_NE(error_of("5", allowed).find("CPU 5 is not one this process may run on (0-1)"), std::string::npos);
  EXPECT_NE(error_of("x", allowed).find("'x' is not a CPU number"), std::string::npos);
  EXPECT_NE(error_of("", allowed).find("'' is not a CPU number"), std::string::npos);
  EXPECT_NE(error_of("1,", allowed).find("'' is not a CPU number"), std::string::npos);
  EXPECT_NE(error_of("-1", allowed).find("'' is not a CPU number"), std::string::npos);
  EXPECT_NE(error_of("1-0", allowed).find("the range '1-0' is empty"), std::string::npos);
  EXPECT_NE(error_of("99999", allowed).find("not a CPU number"), std::string::npos);
  EXPECT_NE(error_of("1024", allowed).find("CPU 1024 is too large (at most 1023)"), std::string::npos);
}

// With SMT, auto takes the last CPU's whole physical core (its siblings the process may use), so the solver
// shares no core with the frames; the core alone when nothing else would remain.
TEST(SolverCpus, AutoTakesAWholeCoreWithItsSiblings) {
  // 4 cores, 2 threads each, numbered as Linux does: CPU c and c + 4 share core c % 4.
  const auto smt = [](int cpu) { return Cpus{cpu % 4, cpu % 4 + 4}; };
  const auto all = split_cpus("auto", {0, 1, 2, 3, 4, 5, 6, 7}, smt);
  ASSERT_TRUE(all);
  EXPECT_EQ(all->solver, (Cpus{3, 7}));
  EXPECT_EQ(all->frames, (Cpus{0, 1, 2, 4, 5, 6}));
  const auto restricted = split_cpus("auto", {0, 1, 2, 5}, smt);  // taskset: CPU 5's sibling 1 is allowed
  ASSERT_TRUE(restricted);
  EXPECT_EQ(restricted->solver, (Cpus{1, 5}));
  EXPECT_EQ(restricted->frames, (Cpus{0, 2}));
  const auto one_core = split_cpus("auto", {3, 7}, smt);  // one core, two threads: its last thread
  ASSERT_TRUE(one_core);
  EXPECT_EQ(one_core->solver, (Cpus{7}));
  EXPECT_EQ(one_core->frames, (Cpus{3}));
  // This machine's own topology always includes the CPU asked about.
  const Cpus own = core_siblings(0);
  EXPECT_NE(std::find(own.begin(), own.end(), 0), own.end());
}

TEST(SolverCpus, ListTextUsesRanges) {
  EXPECT_EQ(cpu_list_text({0, 1, 3}), "0-1,3");
  EXPECT_EQ(cpu_list_text({2}), "2");
  EXPECT_EQ(cpu_list_text({0, 1, 2, 5, 6, 9}), "0-2,5-6,9");
  EXPECT_EQ(cpu_list_text({}), "none");
}

}  // namespace
}  // namespace pushpull::app
