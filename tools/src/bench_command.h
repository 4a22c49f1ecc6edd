// `reeve bench`: its sub-commands' options on the command line.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace reeve {

/// Adds `bench` and its sub-commands to `app`; the returned function runs
/// the one that was parsed and returns the exit code (call it only when
/// the `bench` sub-command was given).
std::function<int()> addBenchCommand(CLI::App& app, CLI::App*& bench);

}  // namespace reeve
