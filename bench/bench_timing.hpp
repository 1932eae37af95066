#pragma once
// Shared timing helpers of the benchmarks (bench_*.cpp): repeated timed batches with a warm-up,
// per-call median / min / p90, a dead-code-elimination barrier, the environment every report
// carries (CPU, compiler, build flags, UTC date), the common command line of the batch
// benchmarks and the JSON report file.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <fstream>
#include <iostream>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/json_writer.hpp"

namespace gaitopt::bench {

using Clock = std::chrono::steady_clock;

// Every measured call's result is accumulated here, so the calls cannot be optimised away.
inline volatile double g_sink = 0.0;

#if defined(__GNUC__) && !defined(__clang__)
inline constexpr const char* kCompiler = "gcc " __VERSION__;
#else
inline constexpr const char* kCompiler = __VERSION__;
#endif
#ifdef NDEBUG
inline constexpr const char* kBuildFlags = "NDEBUG";
#else
inline constexpr const char* kBuildFlags = "assertions on: not a Release build";
#endif

// Forces `value` to be fully materialised in memory: the compiler must assume the asm reads it.
template <class T> inline void escape(const T& value) {
  asm volatile("" : : "g"(&value) : "memory");
}

// Order statistics of a sample (all zero for an empty one).
struct SampleStats {
  double median = 0.0, min = 0.0, p90 = 0.0, max = 0.0, mean = 0.0;
};

inline SampleStats sampleStats(std::vector<double> values) {
  SampleStats s;
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  s.min = values.front();
  s.max = values.back();
  s.median = n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  // Nearest-rank 90th percentile.
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.9 * static_cast<double>(n)));
  s.p90 = values[std::max<std::size_t>(rank, 1) - 1];
  double sum = 0.0;
  for (double v : values) sum += v;
  s.mean = sum / static_cast<double>(n);
  return s;
}

// "met" when `value` is within `target` (at most), "MISSED" otherwise.
inline const char* verdict(double value, double target) {
  return value <= target ? "met" : "MISSED";
}

struct Stats {
  std::string name;
  std::string description;
  double median_ns = 0.0, min_ns = 0.0, p90_ns = 0.0, mean_ns = 0.0;
};

// Per-call times of `repeats` batches of `batch` calls of `call` (a callable returning a double
// that is accumulated into the sink), after one untimed warm-up batch.
template <class Call>
Stats measure(const std::string& name, const std::string& description, int batch, int repeats,
              Call&& call) {
  std::vector<double> per_call;
  per_call.reserve(static_cast<std::size_t>(repeats));
  for (int r = 0; r <= repeats; ++r) {
    double acc = 0.0;
    const Clock::time_point t0 = Clock::now();
    for (int i = 0; i < batch; ++i) acc += call();
    const Clock::time_point t1 = Clock::now();
    g_sink = g_sink + acc;
    if (r == 0) continue;  // warm-up
    per_call.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / batch);
  }
  const SampleStats t = sampleStats(std::move(per_call));
  Stats s;
  s.name = name;
  s.description = description;
  s.min_ns = t.min;
  s.median_ns = t.median;
  s.p90_ns = t.p90;
  s.mean_ns = t.mean;
  return s;
}

// The fields of `s` (name, description, median, min, p90, mean) in the object being written.
inline void writeStatsFields(JsonWriter& w, const Stats& s) {
  w.key("name").value(s.name);
  w.key("description").value(s.description);
  w.key("median_ns").value(s.median_ns);
  w.key("min_ns").value(s.min_ns);
  w.key("p90_ns").value(s.p90_ns);
  w.key("mean_ns").value(s.mean_ns);
}

// The member "results": an array with the fields of every measurement.
inline void writeResultsArray(JsonWriter& w, const std::vector<Stats>& results) {
  w.key("results").beginArray();
  for (const Stats& s : results) {
    w.beginObject();
    writeStatsFields(w, s);
    w.endObject();
  }
  w.endArray();
}

inline std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  for (const char* field : {"model name", "Hardware", "cpu model", "Processor"}) {
    in.clear();
    in.seekg(0);
    while (std::getline(in, line)) {
      if (line.rfind(field, 0) != 0) continue;
      const std::size_t colon = line.find(':');
      if (colon == std::string::npos) continue;
      const std::size_t start = line.find_first_not_of(" \t", colon + 1);
      if (start != std::string::npos) return line.substr(start);
    }
  }
  return "unknown";
}

inline std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// Strictly parsed integer in [1, 1e8] for --batch / --repeats.
inline bool parsePositive(const char* text, int& out) {
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || v < 1 || v > 100000000) return false;
  out = static_cast<int>(v);
  return true;
}

// The UTC date and the CPU a report names, read when the benchmark starts.
struct Environment {
  std::string date = utcNow();
  std::string cpu = cpuModel();
};

// The first lines of a printed report: benchmark and date, CPU, compiler and build flags.
inline void printEnvironment(const char* benchmark, const Environment& env) {
  std::printf("%s  %s\n", benchmark, env.date.c_str());
  std::printf("cpu:       %s\n", env.cpu.c_str());
  std::printf("compiler:  %s (%s)\n", kCompiler, kBuildFlags);
}

// The first members of a JSON report: benchmark, date, cpu, compiler.
inline void writeEnvironment(JsonWriter& w, const char* benchmark, const Environment& env) {
  w.key("benchmark").value(benchmark);
  w.key("date").value(env.date);
  w.key("cpu").value(env.cpu);
  w.key("compiler").value(std::string(kCompiler));
}

// Writes the JSON report `w` to `path` and says so; false (after a message on standard error)
// when the file cannot be written.
inline bool writeJsonReport(const char* benchmark, const std::string& path, const JsonWriter& w) {
  try {
    writeFileAtomically(path, w.str() + "\n");
  } catch (const std::exception& e) {
    std::cerr << benchmark << ": error: cannot write " << path << ": " << e.what() << "\n";
    return false;
  }
  std::printf("JSON written to %s\n", path.c_str());
  return true;
}

// The command line of the batch benchmarks: [--json FILE] [--batch N] [--repeats N] [--help].
struct BatchOptions {
  std::string json_path;
  int batch = 0;
  int repeats = 51;
};

inline void batchUsage(std::ostream& out, const char* benchmark, int default_batch) {
  out << "usage: " << benchmark << " [--json FILE] [--batch N] [--repeats N]\n"
      << "  --json FILE   also write the results as JSON to FILE\n"
      << "  --batch N     calls per timed batch (default " << default_batch << ")\n"
      << "  --repeats N   timed batches per measurement (default 51; >= 31 recommended)\n";
}

// Parses the batch benchmark's command line into `options` (whose batch starts at
// `default_batch`). Returns the exit status when the program is to stop at once: 0 after
// --help (usage on standard output), 2 for a bad argument (usage on standard error).
inline std::optional<int> parseBatchOptions(int argc, char** argv, const char* benchmark,
                                            int default_batch, BatchOptions& options) {
  options.batch = default_batch;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--help" || arg == "-h") {
      batchUsage(std::cout, benchmark, default_batch);
      return 0;
    } else if (arg == "--json" && has_value) {
      options.json_path = argv[++i];
    } else if (arg == "--batch" && has_value && parsePositive(argv[i + 1], options.batch)) {
      ++i;
    } else if (arg == "--repeats" && has_value && parsePositive(argv[i + 1], options.repeats)) {
      ++i;
    } else {
      std::cerr << benchmark << ": bad argument '" << arg << "'\n";
      batchUsage(std::cerr, benchmark, default_batch);
      return 2;
    }
  }
  return std::nullopt;
}

}  // namespace gaitopt::bench
