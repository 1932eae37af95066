#pragma once
// Progress lines of optimisations (SolverSettings::on_iteration).
#include <chrono>
#include <functional>
#include <optional>
#include <ostream>
#include <string>

#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/opt/gait_problem.hpp"

namespace gaitopt::cli {

// How progress lines are shown: on a terminal one line updated in place per stage (`auto`),
// else (or `lines`) one line per report.
enum class ProgressMode { Auto, Lines };

// Prints "[stage] iter k  <progressText>  elapsed t s" for the solver's points. Auto: on a
// terminal one line per stage updated in place (at most every kProgressRefreshSeconds, the
// stage's last point always), otherwise (a log, a pipe) the last line of each stage only;
// Lines: every line. A line evaluates its point, as much work as a solver iteration: only the
// lines shown are made.
class OptimizeProgress {
 public:
  OptimizeProgress(const GaitEvaluator& evaluator, Criterion c, ProgressMode mode,
                   std::ostream& out);
  void report(const std::string& stage, const GaitParameters& p, int iteration);
  void endLine();  // closes an updating line before other output
  std::function<void(const std::string&, const GaitParameters&, int)> hook();

 private:
  enum class Style { InPlace, StageEnds, Every };
  // A report as received; its line is made when shown.
  struct Report {
    std::string stage;
    GaitParameters p;
    int iteration;
    double elapsed;
  };
  std::string line(const Report& r) const;
  void draw(const Report& r);  // InPlace: over the open line
  void endStage();             // shows the stage's last report if it is not shown yet

  const GaitEvaluator& evaluator_;
  Criterion criterion_;
  Style style_;
  std::ostream& out_;
  std::optional<Report> last_;  // the current stage's last report
  bool last_shown_ = false;
  double drawn_at_ = 0.0;  // elapsed time of the last line drawn in place
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace gaitopt::cli
