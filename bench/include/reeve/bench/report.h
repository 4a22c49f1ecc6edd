// What every `reeve bench` sub-command reports with its results: the
// machine and build they were measured on, a table printed aligned and
// written as CSV, and an optional PNG drawn from that CSV by bench/plot.py
// (matplotlib). Nothing here passes or fails on a time.
#pragma once

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace reeve::bench {

/// Where a sub-command writes besides stdout. Empty paths: not written.
struct Output {
  std::filesystem::path csv;   ///< the table, one row per result
  std::filesystem::path plot;  ///< a PNG drawn from the table
  bool force = false;          ///< replace existing files
};

/// An output that cannot be written: a bad path, a full disk, no python3.
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
/// An output that exists while Output::force is false.
struct OutputExists : OutputError {
  using OutputError::OutputError;
};

/// The machine, build and moment of a measurement.
struct Environment {
  std::string cpu;         ///< /proc/cpuinfo "model name", or "unknown"
  std::string compiler;    ///< e.g. "g++ 12.2.0"
  std::string build_type;  ///< CMAKE_BUILD_TYPE of this binary
  std::string date;        ///< local time, ISO 8601
  int threads_used = 1;    ///< the solver is single-threaded
  int hardware_threads = 0;
};

/// The environment of this process, now.
Environment environment();

/// Prints `env` as "# key: value" lines.
void printEnvironment(std::FILE* out, const Environment& env);

/// A table of results. Cells are text (numbers formatted by the caller,
/// an empty cell for a value that does not exist, never "nan" or "inf").
class Table {
 public:
  explicit Table(std::vector<std::string> columns);
  /// Appends a row; throws std::invalid_argument unless it has one cell
  /// per column.
  void add(std::vector<std::string> cells);
  const std::vector<std::string>& columns() const { return columns_; }
  const std::vector<std::vector<std::string>>& rows() const { return rows_; }
  /// Prints the columns aligned, a header line first.
  void print(std::FILE* out) const;
  /// Writes the table as CSV with `env` as the last columns of every row
  /// (cpu, compiler, build_type, date, threads), to a temporary file
  /// renamed onto `path`, so an interrupted run leaves no partial file.
  /// Throws OutputError when it cannot.
  void writeCsv(const std::filesystem::path& path, const Environment& env) const;

 private:
  std::vector<std::string> columns_;
  std::vector<std::vector<std::string>> rows_;
};

/// Throws OutputExists when an output of `out` exists and out.force is
/// false, OutputError when its folder cannot be made or the plot is not a
/// .png; call before measuring.
void checkOutput(const Output& out);

/// Writes the CSV and draws the plot of `kind` ("table1", "trade",
/// "extremes", "scaling") as `out` asks. The plot runs Debian's
/// /usr/bin/python3 (its matplotlib: python3-matplotlib) with the embedded
/// bench/plot.py on the CSV (a temporary one when --csv was not given).
/// Throws OutputError when a file cannot be written or the plot fails.
void writeOutputs(const Output& out, const Table& table, const Environment& env, const std::string& kind);

/// `value` with `digits` significant digits ("%.*g"); "" when not finite.
std::string number(double value, int digits = 4);

}  // namespace reeve::bench
