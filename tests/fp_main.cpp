// GoogleTest main that traps invalid operations, division by zero and
// overflow, so a NaN or Inf born in the solver fails the test where it is
// born instead of propagating silently (DESIGN.md, test habits).
#include <fenv.h>
#include <gtest/gtest.h>

int main(int argc, char** argv) {
  feenableexcept(FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
