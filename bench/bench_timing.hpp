#pragma once
// Shared timing helpers of the benchmarks (bench_*.cpp): repeated timed batches with a warm-up,
// per-call median / min / p90, a dead-code-elimination barrier, and the environment strings
// every report carries (CPU, compiler, build flags, UTC date).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

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
  std::sort(per_call.begin(), per_call.end());
  const std::size_t n = per_call.size();
  Stats s;
  s.name = name;
  s.description = description;
  s.min_ns = per_call.front();
  s.median_ns = n % 2 == 1 ? per_call[n / 2] : 0.5 * (per_call[n / 2 - 1] + per_call[n / 2]);
  // Nearest-rank 90th percentile.
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.9 * static_cast<double>(n)));
  s.p90_ns = per_call[std::max<std::size_t>(rank, 1) - 1];
  double sum = 0.0;
  for (double t : per_call) sum += t;
  s.mean_ns = sum / static_cast<double>(n);
  return s;
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

}  // namespace gaitopt::bench
