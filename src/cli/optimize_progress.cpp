#include "optimize_progress.hpp"

#include <unistd.h>

#include <iostream>

#include "cli_common.hpp"

namespace gaitopt::cli {
namespace {

// A terminal line is redrawn at most this often: a human reads no faster, and each drawing
// evaluates a step.
constexpr double kProgressRefreshSeconds = 0.1;

}  // namespace

OptimizeProgress::OptimizeProgress(const GaitEvaluator& evaluator, Criterion c, ProgressMode mode,
                                   std::ostream& out)
    : evaluator_(evaluator),
      criterion_(c),
      style_(mode == ProgressMode::Lines ? Style::Every
             : &out == &std::cout && isatty(STDOUT_FILENO) ? Style::InPlace
                                                            : Style::StageEnds),
      out_(out) {}

std::string OptimizeProgress::line(const Report& r) const {
  return "[" + r.stage + "] iter " + std::to_string(r.iteration) + "  " +
         progressText(evaluator_, evaluator_.evaluate(r.p), criterion_) + "  elapsed " +
         shortNumber(r.elapsed, "%.1f") + " s";
}

void OptimizeProgress::draw(const Report& r) {
  out_ << "\r" << line(r) << "\033[K" << std::flush;
  drawn_at_ = r.elapsed;
}

void OptimizeProgress::report(const std::string& stage, const GaitParameters& p, int iteration) {
  Report r{stage, p, iteration,
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count()};
  if (style_ == Style::Every) {
    out_ << line(r) << "\n" << std::flush;
    return;
  }
  const bool new_stage = !last_ || last_->stage != stage;
  if (new_stage) endStage();
  last_shown_ = style_ == Style::InPlace &&
                (new_stage || r.elapsed - drawn_at_ >= kProgressRefreshSeconds);
  if (last_shown_) draw(r);
  last_ = std::move(r);
}

void OptimizeProgress::endStage() {
  if (!last_) return;
  if (style_ == Style::StageEnds) out_ << line(*last_) << "\n" << std::flush;
  if (style_ == Style::InPlace) {
    if (!last_shown_) draw(*last_);
    out_ << "\n" << std::flush;  // the last line of each stage stays
  }
  last_.reset();
}

void OptimizeProgress::endLine() { endStage(); }

std::function<void(const std::string&, const GaitParameters&, int)> OptimizeProgress::hook() {
  return [this](const std::string& stage, const GaitParameters& p, int it) {
    report(stage, p, it);
  };
}

}  // namespace gaitopt::cli
