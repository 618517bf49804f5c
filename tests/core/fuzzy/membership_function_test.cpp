// Each membership function at hand-computed points, and its validation.
#include "core/fuzzy/membership_function.h"

#include <gtest/gtest.h>

#include <cmath>

namespace neurocloth::fuzzy {
namespace {

TEST(MembershipFunction, Triangle) {
  const MembershipFunction f{Shape::triangle, {1, 3, 4}};
  EXPECT_EQ(f(0.5), 0.0);
  EXPECT_EQ(f(2), 0.5);
  EXPECT_EQ(f(3), 1.0);
  EXPECT_EQ(f(3.5), 0.5);
  EXPECT_EQ(f(5), 0.0);
  // A left shoulder: a == b is 1 at b.
  EXPECT_EQ((MembershipFunction{Shape::triangle, {0, 0, 10}}(0)), 1.0);
}

TEST(MembershipFunction, Trapezoid) {
  const MembershipFunction f{Shape::trapezoid, {0, 2, 3, 7}};
  EXPECT_EQ(f(1), 0.5);
  EXPECT_EQ(f(2.5), 1.0);
  EXPECT_EQ(f(6), 0.25);
  EXPECT_EQ(f(8), 0.0);
}

TEST(MembershipFunction, PointList) {
  const MembershipFunction f{Shape::points, {0, 1, 2, 0.5, 4, 0.5, 5, 0}};
  EXPECT_EQ(f(-1), 1.0);  // constant outside
  EXPECT_EQ(f(1), 0.75);
  EXPECT_EQ(f(3), 0.5);
  EXPECT_EQ(f(4.5), 0.25);
  EXPECT_EQ(f(9), 0.0);
}

TEST(MembershipFunction, Gaussian) {
  const MembershipFunction f{Shape::gaussian, {2, 0.5}};
  EXPECT_DOUBLE_EQ(f(2), 1.0);
  EXPECT_DOUBLE_EQ(f(2.5), std::exp(-0.5));
  EXPECT_DOUBLE_EQ(f(1), std::exp(-2.0));
}

TEST(MembershipFunction, GeneralisedBell) {
  const MembershipFunction f{Shape::bell, {2, 3, 1}};  // a b c
  EXPECT_DOUBLE_EQ(f(1), 1.0);
  EXPECT_DOUBLE_EQ(f(3), 0.5);  // |(3 - 1) / 2|^6 = 1
  EXPECT_DOUBLE_EQ(f(5), 1.0 / (1.0 + 64.0));
}

TEST(MembershipFunction, Sigmoid) {
  const MembershipFunction f{Shape::sigmoid, {4, 1}};  // gain center
  EXPECT_DOUBLE_EQ(f(1), 0.5);
  EXPECT_DOUBLE_EQ(f(1.5), 1.0 / (1.0 + std::exp(-2.0)));
}

TEST(MembershipFunction, Singleton) {
  const MembershipFunction f{Shape::singleton, {0.3}};
  EXPECT_EQ(f(0.3), 1.0);
  EXPECT_EQ(f(0.31), 0.0);
}

TEST(MembershipFunction, Validation) {
  EXPECT_EQ((MembershipFunction{Shape::triangle, {0, 1, 2}}.validate()), "");
  EXPECT_NE((MembershipFunction{Shape::triangle, {0, 3, 2}}.validate()), "");
  EXPECT_NE((MembershipFunction{Shape::triangle, {0, 1}}.validate()), "");
  EXPECT_NE((MembershipFunction{Shape::trapezoid, {0, 2, 1, 3}}.validate()), "");
  EXPECT_NE((MembershipFunction{Shape::gaussian, {0, 0}}.validate()), "");
  EXPECT_NE((MembershipFunction{Shape::bell, {1, -1, 0}}.validate()), "");
  EXPECT_NE((MembershipFunction{Shape::points, {0, 1, 2}}.validate()), "");
  EXPECT_NE((MembershipFunction{Shape::points, {0, 1.5}}.validate()), "");
  EXPECT_NE((MembershipFunction{Shape::points, {2, 1, 1, 0}}.validate()), "");
  EXPECT_NE((MembershipFunction{Shape::triangle, {0, NAN, 1}}.validate()), "");
}

TEST(MembershipFunction, BreakpointsOfPiecewiseLinearShapes) {
  EXPECT_EQ((MembershipFunction{Shape::points, {0, 1, 2, 0.5}}.breakpoints()),
            (std::vector<double>{0, 2}));
  EXPECT_EQ((MembershipFunction{Shape::trapezoid, {0, 1, 2, 3}}.breakpoints()),
            (std::vector<double>{0, 1, 2, 3}));
  EXPECT_TRUE((MembershipFunction{Shape::gaussian, {0, 1}}.breakpoints().empty()));
}

}  // namespace
}  // namespace neurocloth::fuzzy
