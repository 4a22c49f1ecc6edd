// Scoped masking of floating-point exceptions.
#pragma once

#include <cfenv>

namespace reeve {

/// Masks floating-point exceptions while it lives, then restores the
/// caller's environment: its traps, and its flags as they were (those
/// raised meanwhile are forgotten). For code that overflows by design and
/// tests the result (a loader asking whether a mass is representable), and
/// for libraries that raise exceptions as a matter of course (strtod on
/// "1e999", Mesa's pipeline), so that a program trapping exceptions
/// (tests/fp_main.cpp, REEVE_TRAP_FP) keeps them trapped everywhere else.
class FloatingPointExceptionsMasked {
 public:
  FloatingPointExceptionsMasked() { std::feholdexcept(&saved_); }
  ~FloatingPointExceptionsMasked() { std::fesetenv(&saved_); }
  FloatingPointExceptionsMasked(const FloatingPointExceptionsMasked&) = delete;
  FloatingPointExceptionsMasked& operator=(const FloatingPointExceptionsMasked&) = delete;

 private:
  std::fenv_t saved_;
};

}  // namespace reeve
