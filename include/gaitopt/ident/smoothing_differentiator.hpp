#pragma once
// Zero-phase smoothing differentiator for measured angles: a Savitzky–Golay filter generalised
// to irregular times. At each sample, the least-squares polynomial of degree `order` through
// the samples of the same segment (one phase of one step) within ±half_window seconds — the
// window slides inward near segment ends and shrinks to the whole segment when that is shorter
// — gives the smoothed value and its first two derivatives there (degree lowered to n/5, at
// least 2, for a window of n < 5 × degree samples). Linear in the signal: the
// per-sample weights are computed once and applied to any number of signals.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/ident/effects.hpp"
#include "gaitopt/ident/measured_data.hpp"

namespace gaitopt {

// A maximal run of samples with the same step, phase and stance.
struct Segment {
  std::size_t begin = 0, end = 0;  // [begin, end)
  Phase phase = Phase::SingleSupport;
  Stance stance = Stance::Left;
  long step = 0;
};
std::vector<Segment> dataSegments(const MeasuredData& data);

struct SmoothedSignal {
  std::vector<double> value, first, second;
};

class SmoothingDifferentiator {
 public:
  SmoothingDifferentiator(const std::vector<double>& t, const std::vector<Segment>& segments,
                          double half_window, int order);
  SmoothedSignal apply(const std::vector<double>& x) const;
  double halfWindow() const { return half_window_; }
  int order() const { return order_; }

 private:
  struct Weights {
    std::size_t first = 0;
    Eigen::Matrix<double, 3, Eigen::Dynamic> w;  // value, first, second derivative
  };
  std::vector<Weights> rows_;
  double half_window_;
  int order_;
};

// Smoothed q, q̇, q̈ of measured configurations.
struct Kinematics {
  std::vector<Vec5> q, qd, qdd;
};
Kinematics differentiate(const SmoothingDifferentiator& d, const std::vector<Vec5>& q);

}  // namespace gaitopt
