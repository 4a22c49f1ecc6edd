// Compiled for AVX2 and FMA (tests/CMakeLists.txt), with the build's own
// floating-point options: test_fp_contract.cpp calls it where the CPU has
// both.
namespace reeve::test_fp_contract {

double wideMultiplyAdd(double a, double b, double c) { return a * b + c; }

}  // namespace reeve::test_fp_contract
