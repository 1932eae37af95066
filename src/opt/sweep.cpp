#include "gaitopt/opt/sweep.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "gaitopt/gait/summary.hpp"
#include "gaitopt/opt/initial_guess.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/json_writer.hpp"

namespace gaitopt {
namespace {

constexpr int kMaxSpeeds = 10000;
constexpr double kDuplicateTol = 1e-9;  // m/s

constexpr std::size_t kMaxCsvLineBytes = 4096;
const std::array<const char*, 4> kStatuses = {"optimal", "infeasible", "max_iter", "failed"};

// A decimal number as written in a CSV field or on the command line: digits, sign, point and
// exponent only (no spaces, hex, inf or nan), finite. Empty when it is not one.
std::optional<double> decimal(const std::string& field) {
  if (field.empty() || field.size() > 64 ||
      field.find_first_not_of("0123456789+-.eE") != std::string::npos)
    return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(field.c_str(), &end);
  if (end != field.c_str() + field.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

double parseNumber(const std::string& field, const std::string& what, const std::string& text) {
  const std::optional<double> v = decimal(field);
  if (!v)
    throw std::invalid_argument("speed range '" + printable(text) + "': " + what + " '" +
                                printable(field) + "' is not a finite number");
  return *v;
}

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::string::size_type begin = 0;
  while (true) {
    const auto end = text.find(sep, begin);
    out.push_back(text.substr(begin, end == std::string::npos ? std::string::npos : end - begin));
    if (end == std::string::npos) break;
    begin = end + 1;
  }
  return out;
}

bool isOptimal(const SweepPoint& p) { return p.attempts > 0 && p.result.status == "optimal"; }

// Which of two attempts to keep: an optimal one, else the smaller constraint violation (the
// earlier one on ties).
bool better(const OptimizationResult& candidate, const OptimizationResult& kept) {
  if (kept.status == "optimal") return false;
  if (candidate.status == "optimal") return true;
  return candidate.constraint_violation < kept.constraint_violation;
}

// The serialised progress reporting shared by the chains.
struct ProgressSink {
  ProgressSink(const ProgressFn& f, int n)
      : fn(&f), t0(std::chrono::steady_clock::now()), total(n) {}
  const ProgressFn* fn;
  std::chrono::steady_clock::time_point t0;
  int total;
  int done = 0;
  std::mutex mutex;

  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  void point(const SweepPoint& p) {
    std::lock_guard<std::mutex> lock(mutex);
    ++done;
    if (*fn) (*fn)(SweepProgress{false, p, done, total, elapsed()});
  }
};

struct FreeStart {
  bool optimal = false;
  bool has_speed = false;
  double speed = 0.0;
  GaitParameters parameters;
};

// One chain over the sorted speeds of a chunk.
class Chain {
 public:
  Chain(const GaitEvaluator& ev, const OptimizationRequest& base, const FreeStart& free,
        const std::vector<double>& speeds, ProgressSink& sink)
      : ev_(ev), base_(base), free_(free), speeds_(speeds), sink_(sink), points_(speeds.size()) {
    for (std::size_t i = 0; i < speeds.size(); ++i) points_[i].speed = speeds[i];
  }

  std::vector<SweepPoint> run() {
    const int n = static_cast<int>(speeds_.size());
    if (n == 0) return {};
    const int s = startIndex();
    std::vector<int> order{s};
    for (int i = s + 1; i < n; ++i) order.push_back(i);
    for (int i = s - 1; i >= 0; --i) order.push_back(i);

    // Walk: the start from the free-speed optimum, then outward from the last optimum.
    if (free_.optimal)
      attempt(s, free_.parameters, free_.speed, false);
    else
      attempt(s, defaultGuess(s), kNaN, false);
    if (isOptimal(points_[s])) sink_.point(points_[s]);
    for (int dir : {+1, -1}) {
      int anchor = isOptimal(points_[s]) ? s : -1;
      for (int i = s + dir; i >= 0 && i < n; i += dir) {
        if (anchor >= 0)
          attempt(i, points_[anchor].result.parameters, speeds_[anchor], true);
        else if (free_.optimal)
          attempt(i, free_.parameters, free_.speed, false);
        else
          attempt(i, defaultGuess(i), kNaN, false);
        if (isOptimal(points_[i])) {
          anchor = i;
          sink_.point(points_[i]);
        }
      }
    }

    // Retries, in walk order: from the nearest optimum beyond the speed, then from the default
    // initial guess.
    for (int i : order) {
      if (isOptimal(points_[i])) continue;
      const int beyond = nearestOptimumBeyond(i, s);
      if (beyond >= 0) attempt(i, points_[beyond].result.parameters, speeds_[beyond], true);
      if (!isOptimal(points_[i]) && !tried_default_[i]) attempt(i, defaultGuess(i), kNaN, false);
      sink_.point(points_[i]);
    }
    return points_;
  }

 private:
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  int startIndex() const {
    const int n = static_cast<int>(speeds_.size());
    if (!free_.has_speed) return (n - 1) / 2;
    int best = 0;
    for (int i = 1; i < n; ++i)
      if (std::abs(speeds_[i] - free_.speed) < std::abs(speeds_[best] - free_.speed)) best = i;
    return best;
  }

  // Nearest optimal speed on the far side of i from the start s (either side for s itself,
  // the closer in speed, the lower on ties); −1 if none.
  int nearestOptimumBeyond(int i, int s) const {
    const int n = static_cast<int>(speeds_.size());
    int up = -1, down = -1;
    if (i >= s)
      for (int j = i + 1; j < n && up < 0; ++j)
        if (isOptimal(points_[j])) up = j;
    if (i <= s)
      for (int j = i - 1; j >= 0 && down < 0; --j)
        if (isOptimal(points_[j])) down = j;
    if (up < 0) return down;
    if (down < 0) return up;
    return speeds_[up] - speeds_[i] < speeds_[i] - speeds_[down] ? up : down;
  }

  GaitParameters defaultGuess(int i) {
    tried_default_[i] = true;
    return defaultInitialGuess(ev_.model(), speeds_[i]);
  }

  void attempt(int i, const GaitParameters& start, double from_speed, bool warm) {
    OptimizationRequest req = base_;
    req.speed = speeds_[i];
    req.initial = start;
    OptimizationResult r = optimizeGait(ev_, req, nullptr);
    SweepPoint& p = points_[i];
    ++p.attempts;
    p.total_iterations += r.iterations;
    p.total_wall_time_s += r.wall_time_s;
    if (p.attempts == 1 || better(r, p.result)) {
      p.result = std::move(r);
      p.warm_started = warm;
      p.from_speed = from_speed;
    }
  }

  const GaitEvaluator& ev_;
  const OptimizationRequest& base_;
  const FreeStart& free_;
  const std::vector<double>& speeds_;
  ProgressSink& sink_;
  std::vector<SweepPoint> points_;
  std::vector<bool> tried_default_ = std::vector<bool>(speeds_.size(), false);
};

// `v` with six significant digits, as a user would write it ("0.2", not 0.20000000000000001).
std::string formatShort(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string field(bool available, double v) {
  return available && std::isfinite(v) ? formatDouble(v) : "";
}

}  // namespace

std::vector<double> parseSpeedRange(const std::string& text) {
  const std::vector<std::string> f = split(text, ':');
  if (f.size() != 3)
    throw std::invalid_argument("speed range '" + text +
                                "': expected start:stop:step in m/s, e.g. 0.2:1.0:0.05");
  const double start = parseNumber(f[0], "start", text);
  const double stop = parseNumber(f[1], "stop", text);
  const double step = parseNumber(f[2], "step", text);
  if (start <= 0.0)
    throw std::invalid_argument("speed range '" + text + "': start must be > 0 m/s");
  if (stop < start)
    throw std::invalid_argument("speed range '" + text + "': stop must be >= start");
  if (stop > kMaxWalkingSpeed)
    throw std::invalid_argument("speed range '" + text + "': stop must be <= " +
                                formatShort(kMaxWalkingSpeed) + " m/s");
  if (step <= 0.0) throw std::invalid_argument("speed range '" + text + "': step must be > 0 m/s");
  const double intervals = std::floor((stop - start) / step + 1e-9);
  if (intervals + 1.0 > kMaxSpeeds)
    throw std::invalid_argument("speed range '" + text + "': more than " +
                                std::to_string(kMaxSpeeds) + " speeds");
  std::vector<double> out;
  for (int k = 0; k <= static_cast<int>(intervals); ++k)
    out.push_back(std::round((start + k * step) * 1e12) / 1e12);
  return out;
}

Shard parseShard(const std::string& text) {
  const std::vector<std::string> f = split(text, '/');
  auto integer = [&](const std::string& s, const char* what) {
    if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos)
      throw std::invalid_argument("shard '" + printable(text) + "': " + what + " '" +
                                  printable(s) +
                                  "' is not a non-negative integer (expected i/n, i = 0 … n-1)");
    if (s.size() > 5 || std::stoi(s) > kMaxSpeeds)
      throw std::invalid_argument("shard '" + text + "': " + what + " " + s + " exceeds " +
                                  std::to_string(kMaxSpeeds) + ", the largest number of speeds");
    return std::stoi(s);
  };
  if (f.size() != 2)
    throw std::invalid_argument("shard '" + printable(text) +
                                "': expected i/n with 0 <= i < n, e.g. 0/4");
  Shard shard{integer(f[0], "index"), integer(f[1], "count")};
  if (shard.count < 1) throw std::invalid_argument("shard '" + text + "': n must be >= 1");
  if (shard.index >= shard.count)
    throw std::invalid_argument("shard '" + text + "': index must be < n (0-based: 0 … " +
                                std::to_string(shard.count - 1) + ")");
  return shard;
}

std::vector<std::vector<double>> splitContiguous(const std::vector<double>& sorted, int count) {
  const int n = static_cast<int>(sorted.size());
  if (count < 1 || count > n)
    throw std::invalid_argument("cannot split " + std::to_string(n) + " speed(s) into " +
                                std::to_string(count) + " chunk(s): need 1 <= chunks <= speeds");
  std::vector<std::vector<double>> chunks;
  for (int k = 0; k < count; ++k) {
    // Floor boundaries: the earlier chunks are the smaller ones.
    const int begin = static_cast<int>(static_cast<long long>(k) * n / count);
    const int end = static_cast<int>(static_cast<long long>(k + 1) * n / count);
    chunks.emplace_back(sorted.begin() + begin, sorted.begin() + end);
  }
  return chunks;
}

std::vector<double> sortedSpeeds(const std::vector<double>& speeds) {
  if (speeds.empty()) throw std::invalid_argument("no speeds to sweep");
  std::vector<double> s = speeds;
  for (double v : s)
    if (!std::isfinite(v) || v <= 0.0)
      throw std::invalid_argument("sweep speed " + formatShort(v) + " is not > 0 m/s");
  std::sort(s.begin(), s.end());
  for (std::size_t i = 1; i < s.size(); ++i)
    if (s[i] - s[i - 1] <= kDuplicateTol)
      throw std::invalid_argument("sweep speed " + formatShort(s[i]) + " m/s appears twice");
  return s;
}

std::vector<double> sweepRunSpeeds(const std::vector<double>& speeds,
                                   const SweepSettings& settings) {
  std::vector<double> s = sortedSpeeds(speeds);
  if (settings.jobs < 1) throw std::invalid_argument("jobs must be >= 1");
  if (!settings.sharded) return s;
  if (settings.shard.count < 1 || settings.shard.index < 0 ||
      settings.shard.index >= settings.shard.count)
    throw std::invalid_argument("shard " + std::to_string(settings.shard.index) + "/" +
                                std::to_string(settings.shard.count) + ": expected 0 <= i < n");
  if (settings.shard.count > static_cast<int>(s.size()))
    throw std::invalid_argument("shard count " + std::to_string(settings.shard.count) +
                                " exceeds the number of speeds (" + std::to_string(s.size()) + ")");
  return splitContiguous(s, settings.shard.count)[settings.shard.index];
}

std::vector<SweepPoint> sweepSpeeds(const GaitEvaluator& ev, const OptimizationRequest& base,
                                    const std::vector<double>& speeds,
                                    const SweepSettings& settings, const ProgressFn& progress) {
  const std::vector<double> run = sweepRunSpeeds(speeds, settings);
  ProgressSink sink(progress, static_cast<int>(run.size()));

  // (a) the free-speed optimum, once.
  OptimizationRequest free_request = base;
  free_request.speed.reset();
  SweepPoint free_point;
  free_point.result = optimizeGait(ev, free_request, nullptr);
  free_point.attempts = 1;
  free_point.total_iterations = free_point.result.iterations;
  free_point.total_wall_time_s = free_point.result.wall_time_s;
  free_point.from_speed = std::numeric_limits<double>::quiet_NaN();
  FreeStart free;
  free.optimal = free_point.result.status == "optimal";
  free.has_speed = zeroDynamicsComputed(ev, free_point.result.evaluation) &&
                   std::isfinite(free_point.result.evaluation.speed);
  free.speed = free.has_speed ? free_point.result.evaluation.speed : 0.0;
  free.parameters = free_point.result.parameters;
  free_point.speed = free.has_speed ? free.speed : std::numeric_limits<double>::quiet_NaN();
  if (progress) progress(SweepProgress{true, free_point, 0, sink.total, sink.elapsed()});

  const int jobs = std::min(settings.jobs, static_cast<int>(run.size()));
  const std::vector<std::vector<double>> chunks = splitContiguous(run, jobs);
  std::vector<std::vector<SweepPoint>> results(chunks.size());
  const bool concurrent = jobs > 1 && base.solver.backend != Backend::Ipopt;
  if (jobs > 1 && !concurrent && settings.warnings)
    *settings.warnings << "warning: speed sweep: backend ipopt is not known to be thread-safe "
                          "(sequential MUMPS): the "
                       << jobs << " chains run one after the other\n";
  if (concurrent) {
    std::vector<std::exception_ptr> errors(chunks.size());
    std::vector<std::thread> threads;
    for (std::size_t c = 0; c < chunks.size(); ++c)
      threads.emplace_back([&, c]() {
        try {
          results[c] = Chain(ev, base, free, chunks[c], sink).run();
        } catch (...) {
          errors[c] = std::current_exception();
        }
      });
    for (std::thread& t : threads) t.join();
    for (const std::exception_ptr& e : errors)
      if (e) std::rethrow_exception(e);
  } else {
    for (std::size_t c = 0; c < chunks.size(); ++c)
      results[c] = Chain(ev, base, free, chunks[c], sink).run();
  }
  std::vector<SweepPoint> out;
  for (std::vector<SweepPoint>& r : results)
    for (SweepPoint& p : r) out.push_back(std::move(p));
  return out;
}

const char* const kSweepCsvHeader =
    "speed,status,C_Gamma,C_E,W,C_frott,step_length,T_SS,T_DS,iterations,wall_time_s";

std::string sweepCsvRow(const GaitEvaluator& ev, const SweepPoint& p) {
  const GaitEvaluation<double>& e = p.result.evaluation;
  const bool criteria = e.defined() && e.motion_computed;
  const bool timing = zeroDynamicsComputed(ev, e);
  std::ostringstream row;
  row << formatDouble(p.speed) << ',' << p.result.status << ',' << field(criteria, e.C_Gamma) << ','
      << field(criteria, e.C_E) << ',' << field(criteria, e.W) << ',' << field(criteria, e.C_frott)
      << ',' << field(true, p.result.parameters[kStepLength]) << ',' << field(timing, e.T_SS) << ','
      << field(true, p.result.parameters[kTDS]) << ',' << p.total_iterations << ','
      << formatDouble(p.total_wall_time_s);
  return row.str();
}

std::string sweepCsv(const GaitEvaluator& ev, const std::vector<SweepPoint>& points) {
  std::string out = std::string(kSweepCsvHeader) + "\n";
  for (const SweepPoint& p : points) out += sweepCsvRow(ev, p) + "\n";
  return out;
}

namespace {

// One row of a sweep.csv, every column typed and range-checked (README, "Merging shards");
// throws std::invalid_argument naming `where` (file:line) and the column. Returns the speed.
double checkSweepRow(const std::vector<std::string>& f, const std::string& where) {
  const std::vector<std::string> names = split(kSweepCsvHeader, ',');
  const auto bad = [&](std::size_t c, const std::string& problem) {
    return std::invalid_argument(where + ": column " + names[c] + ": '" + printable(f[c]) +
                                 "' " + problem);
  };
  const std::optional<double> speed = decimal(f[0]);
  if (!speed || !(*speed > 0.0) || *speed > kMaxWalkingSpeed)
    throw bad(0, "is not a speed in (0, " + formatShort(kMaxWalkingSpeed) + "] m/s");
  if (std::find(kStatuses.begin(), kStatuses.end(), f[1]) == kStatuses.end())
    throw bad(1, "is not a status (optimal, infeasible, max_iter, failed)");
  for (std::size_t c = 2; c <= 8; ++c) {  // criteria, step length, phase durations
    const std::optional<double> v = decimal(f[c]);
    if (!f[c].empty() && (!v || (c >= 7 && *v < 0.0)))
      throw bad(c, c >= 7 ? "is not a duration >= 0 s (or empty)" : "is not a number (or empty)");
  }
  if (f[9].empty() || f[9].size() > 9 || f[9].find_first_not_of("0123456789") != std::string::npos)
    throw bad(9, "is not a non-negative integer");
  const std::optional<double> wall = decimal(f[10]);
  if (!wall || *wall < 0.0) throw bad(10, "is not a duration >= 0 s");
  return *speed;
}

}  // namespace

std::string mergeSweepCsvs(const std::vector<std::string>& texts,
                           const std::vector<std::string>& names) {
  const std::size_t columns = split(kSweepCsvHeader, ',').size();
  std::vector<std::pair<double, std::string>> rows;
  std::vector<std::string> origin;
  for (std::size_t t = 0; t < texts.size(); ++t) {
    const std::string name =
        printable(t < names.size() ? names[t] : "input " + std::to_string(t + 1));
    if (texts[t].size() > kMaxSweepCsvBytes)
      throw std::invalid_argument(name + ": larger than " + std::to_string(kMaxSweepCsvBytes) +
                                  " bytes (limit)");
    std::istringstream in(texts[t]);
    std::string line;
    if (!std::getline(in, line)) throw std::invalid_argument(name + ": empty file, no header");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line != kSweepCsvHeader)
      throw std::invalid_argument(name + ": header '" + printable(line) + "' differs from '" +
                                  kSweepCsvHeader + "'");
    int line_no = 1;
    while (std::getline(in, line)) {
      ++line_no;
      const std::string where = name + ":" + std::to_string(line_no);
      if (line.size() > kMaxCsvLineBytes)
        throw std::invalid_argument(where + ": line longer than " +
                                    std::to_string(kMaxCsvLineBytes) + " bytes (limit)");
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.empty()) continue;
      const std::vector<std::string> f = split(line, ',');
      if (f.size() != columns)
        throw std::invalid_argument(where + ": expected " + std::to_string(columns) +
                                    " fields, got " + std::to_string(f.size()));
      if (static_cast<int>(rows.size()) >= kMaxSpeeds)
        throw std::invalid_argument(where + ": more than " + std::to_string(kMaxSpeeds) +
                                    " rows (limit)");
      rows.emplace_back(checkSweepRow(f, where), line);
      origin.push_back(where);
    }
  }
  std::vector<std::size_t> idx(rows.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::stable_sort(idx.begin(), idx.end(),
                   [&](std::size_t a, std::size_t b) { return rows[a].first < rows[b].first; });
  std::string out = std::string(kSweepCsvHeader) + "\n";
  for (std::size_t k = 0; k < idx.size(); ++k) {
    if (k > 0 && rows[idx[k]].first - rows[idx[k - 1]].first <= kDuplicateTol)
      throw std::invalid_argument("speed " + formatShort(rows[idx[k]].first) + " appears twice: " +
                                  origin[idx[k - 1]] + " and " + origin[idx[k]]);
    out += rows[idx[k]].second + "\n";
  }
  return out;
}

std::string sweepFolderName(double speed, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "v%.*f", decimals, speed);
  return buf;
}

int sweepFolderDecimals(const std::vector<double>& speeds) {
  for (int d = 3; d < 12; ++d) {
    std::vector<std::string> names;
    for (double v : speeds) names.push_back(sweepFolderName(v, d));
    std::sort(names.begin(), names.end());
    if (std::adjacent_find(names.begin(), names.end()) == names.end()) return d;
  }
  return 12;
}

}  // namespace gaitopt
