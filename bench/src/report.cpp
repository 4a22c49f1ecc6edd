#include "reeve/bench/report.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <thread>
#include <unistd.h>

#include "plot_script.h"

namespace reeve::bench {
namespace {

namespace fs = std::filesystem;

std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  return "unknown";
}

std::string compiler() {
#if defined(__clang__)
  return std::string("clang++ ") + __clang_version__;
#elif defined(__GNUC__)
  return std::string("g++ ") + __VERSION__;
#else
  return "unknown";
#endif
}

// CSV quoting (RFC 4180) where a cell needs it.
std::string csvCell(const std::string& cell) {
  if (cell.find_first_of(",\"\r\n") == std::string::npos) return cell;
  std::string quoted = "\"";
  for (char c : cell) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

void writeRow(std::ostream& out, const std::vector<std::string>& cells) {
  for (std::size_t i = 0; i < cells.size(); ++i) out << (i ? "," : "") << csvCell(cells[i]);
  out << '\n';
}

// A temporary file beside `path`, renamed onto it once complete.
fs::path partialPath(const fs::path& path) {
  std::string name = ".";  // not "." + name: g++ 12's -Wrestrict misfires on it
  name += path.filename().string();
  name += ".partial-" + std::to_string(::getpid());
  return path.parent_path() / name;
}

void commit(const fs::path& partial, const fs::path& path) {
  std::error_code ec;
  fs::rename(partial, path, ec);
  if (ec) {
    fs::remove(partial, ec);
    throw OutputError(path.string() + ": cannot write: " + ec.message());
  }
}

void refuse(const fs::path& path, bool force) {
  if (path.empty()) return;
  if (!force && fs::exists(path)) throw OutputExists(path.string() + ": exists; pass --force to overwrite it");
  if (fs::is_directory(path)) throw OutputError(path.string() + ": is a folder, expected a file name");
  std::error_code ec;
  if (path.has_parent_path()) fs::create_directories(path.parent_path(), ec);
  if (ec) throw OutputError(path.parent_path().string() + ": cannot create: " + ec.message());
}

// `text` as one word for sh.
std::string shellQuoted(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

void plot(const fs::path& csv, const fs::path& png, const std::string& kind) {
  const fs::path partial = partialPath(png);
  const std::string command =
      "/usr/bin/python3 - " + shellQuoted(kind) + " " + shellQuoted(csv.string()) + " " + shellQuoted(partial.string());
  std::FILE* pipe = ::popen(command.c_str(), "w");
  if (!pipe) throw OutputError(png.string() + ": cannot start /usr/bin/python3: " + std::strerror(errno));
  std::fwrite(kPlotScript.data(), 1, kPlotScript.size(), pipe);
  const int status = ::pclose(pipe);
  if (status != 0) {
    std::error_code ec;
    fs::remove(partial, ec);
    throw OutputError(png.string() + ": plotting failed (it needs Debian's python3-matplotlib: bash tools/setup.sh)");
  }
  commit(partial, png);
}

}  // namespace

Environment environment() {
  Environment env;
  env.cpu = cpuModel();
  env.compiler = compiler();
  env.build_type = REEVE_BUILD_TYPE;
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%S%z", std::localtime(&now));
  env.date = date;
  env.hardware_threads = static_cast<int>(std::thread::hardware_concurrency());
  return env;
}

void printEnvironment(std::FILE* out, const Environment& env) {
  std::fprintf(out, "# cpu: %s\n# compiler: %s\n# build type: %s\n# date: %s\n# threads: %d used of %d\n",
               env.cpu.c_str(), env.compiler.c_str(), env.build_type.c_str(), env.date.c_str(), env.threads_used,
               env.hardware_threads);
}

Table::Table(std::vector<std::string> columns) : columns_(std::move(columns)) {}

void Table::add(std::vector<std::string> cells) {
  if (cells.size() != columns_.size())
    throw std::invalid_argument("Table::add: " + std::to_string(cells.size()) + " cells for " +
                                std::to_string(columns_.size()) + " columns");
  rows_.push_back(std::move(cells));
}

void Table::print(std::FILE* out) const {
  std::vector<std::size_t> width(columns_.size());
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    width[c] = columns_[c].size();
    for (const auto& row : rows_) width[c] = std::max(width[c], row[c].size());
  }
  const auto line = [&](const std::vector<std::string>& cells) {
    for (std::size_t c = 0; c < cells.size(); ++c)
      std::fprintf(out, c == 0 ? "%-*s" : "  %*s", static_cast<int>(width[c]), cells[c].c_str());
    std::fputc('\n', out);
  };
  line(columns_);
  for (const auto& row : rows_) line(row);
}

void Table::writeCsv(const fs::path& path, const Environment& env) const {
  const fs::path partial = partialPath(path);
  {
    std::ofstream out(partial);
    std::vector<std::string> header = columns_;
    header.insert(header.end(), {"cpu", "compiler", "build_type", "date", "threads"});
    writeRow(out, header);
    for (std::vector<std::string> row : rows_) {
      row.insert(row.end(), {env.cpu, env.compiler, env.build_type, env.date, std::to_string(env.threads_used)});
      writeRow(out, row);
    }
    out.flush();
    if (!out) {
      std::error_code ec;
      fs::remove(partial, ec);
      throw OutputError(path.string() + ": cannot write: " + std::strerror(errno));
    }
  }
  commit(partial, path);
}

void checkOutput(const Output& out) {
  refuse(out.csv, out.force);
  refuse(out.plot, out.force);
  if (!out.plot.empty() && out.plot.extension() != ".png")
    throw OutputError(out.plot.string() + ": expected a file name ending in .png");
}

void writeOutputs(const Output& out, const Table& table, const Environment& env, const std::string& kind) {
  if (!out.csv.empty()) {
    table.writeCsv(out.csv, env);
    std::printf("wrote %s\n", out.csv.c_str());
  }
  if (out.plot.empty()) return;
  fs::path csv = out.csv;
  const bool temporary = csv.empty();
  if (temporary) {
    csv = fs::temp_directory_path() / ("reeve-bench-" + std::to_string(::getpid()) + ".csv");
    table.writeCsv(csv, env);
  }
  try {
    plot(csv, out.plot, kind);
  } catch (...) {
    std::error_code ec;
    if (temporary) fs::remove(csv, ec);
    throw;
  }
  std::error_code ec;
  if (temporary) fs::remove(csv, ec);
  std::printf("wrote %s\n", out.plot.c_str());
}

std::string number(double value, int digits) {
  if (!std::isfinite(value)) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, value);
  return buf;
}

}  // namespace reeve::bench
