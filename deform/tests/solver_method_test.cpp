// Method names round-trip; unknown names are refused with the list of valid ones.
#include <gtest/gtest.h>

#include "pushpull/deform/method.hpp"

namespace pushpull::deform {
namespace {

TEST(SolverMethod, NamesRoundTrip) {
  for (Method m : kAllMethods) EXPECT_EQ(parse_method(method_name(m)), m);
  EXPECT_EQ(parse_method("asan"), Method::Asan);
  EXPECT_EQ(parse_method("sr-arap"), Method::SrArap);
}

TEST(SolverMethod, UnknownNameListsValidOnes) {
  try {
    (void)parse_method("arap-x");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("arap-x"), std::string::npos);
    for (Method m : kAllMethods) EXPECT_NE(what.find(method_name(m)), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace pushpull::deform
