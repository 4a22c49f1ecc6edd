// The `reeve` program run as a user runs it, from a test: its exit code
// and what it printed, in a fresh folder per test.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace test {

namespace fs = std::filesystem;

struct Result {
  int code;
  std::string out, err;
};

// The whole of a file (empty if it cannot be read).
inline std::string slurp(const std::string& file) {
  std::ifstream f(file);
  return {std::istreambuf_iterator<char>(f), {}};
}

// Runs `reeve ARGS` through the shell with stdout and stderr captured in
// files named after the running test, so tests may run in parallel; with
// floating-point traps on (REEVE_TRAP_FP=1, unless `env` sets it), as in
// fp_main.cpp.
inline Result reeve(const std::string& args, const std::string& env = "") {
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const fs::path dir = fs::temp_directory_path();
  const std::string out = (dir / ("reeve_cli_out_" + test + ".txt")).string();
  const std::string err = (dir / ("reeve_cli_err_" + test + ".txt")).string();
  const std::string traps = env.find("REEVE_TRAP_FP") == std::string::npos ? " REEVE_TRAP_FP=1 " : " ";
  const std::string cmd = env + traps + REEVE_BINARY " " + args + " >" + out + " 2>" + err;
  const int status = std::system(cmd.c_str());
  Result r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
  fs::remove(out);
  fs::remove(err);
  return r;
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("reeve_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
    return path(name);
  }
  fs::path dir_;
};

}  // namespace test
