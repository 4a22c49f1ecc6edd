// The build rounds as the tests check it whatever the target (CMakeLists.txt,
// -ffp-contract=off): a multiply and an add compiled for a CPU with fused
// multiply-adds (fp_contract_wide.cpp, -mavx2 -mfma, as -march=native
// compiles on most x86-64 machines and every aarch64 one) round the product
// first. Contracted, the thin rod of test_contacts.cpp slid off its wheel.
#include <gtest/gtest.h>

#include <cmath>

namespace reeve::test_fp_contract {

double wideMultiplyAdd(double a, double b, double c);  // fp_contract_wide.cpp

namespace {

TEST(FpContract, AMultiplyAndAnAddCompiledForFmaRoundTheProductFirst) {
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma"))
    GTEST_SKIP() << "this CPU has no AVX2 and FMA to run code compiled for them";
  // (1 + e)(1 - e) = 1 - e^2 rounds to 1 (e = 2^-30): rounded first, the
  // sum with -1 is 0; fused, it is -e^2.
  const double e = std::ldexp(1.0, -30);
  volatile double a = 1.0 + e, b = 1.0 - e, c = -1.0;
  EXPECT_EQ(a * b + c, 0.0);
  EXPECT_EQ(wideMultiplyAdd(a, b, c), 0.0);
}

}  // namespace
}  // namespace reeve::test_fp_contract
