#pragma once
// Cubic smoothing spline (Reinsch 1967; Green & Silverman 1994, §2.3): the natural cubic
// spline g minimising Σ_i (y_i − g(t_i))² + λ ∫ g''(t)² dt, fitted to several channels that
// share the sample times. Used to resample measured kinematics to another rate with smooth
// velocities and accelerations (zero phase: the fit is symmetric in time).
#include <Eigen/Core>

namespace gaitopt {

class SmoothingSpline {
 public:
  // Fits every column of `y` (n × channels) sampled at strictly increasing `t` (n ≥ 3);
  // λ ≥ 0 (0 interpolates). Throws std::invalid_argument otherwise.
  SmoothingSpline(const Eigen::VectorXd& t, const Eigen::MatrixXd& y, double lambda);

  // Value (order 0), first (1) or second (2) time derivative of every channel at `s`. Outside
  // [t_0, t_{n-1}] the end pieces are extended (linearly: the natural spline has g'' = 0 there).
  Eigen::RowVectorXd evaluate(double s, int order = 0) const;
  // The same at each time of `s`: rows = times, columns = channels.
  Eigen::MatrixXd evaluate(const Eigen::VectorXd& s, int order = 0) const;

 private:
  Eigen::VectorXd t_;
  Eigen::MatrixXd g_;      // fitted values at the knots
  Eigen::MatrixXd gamma_;  // second derivatives at the knots (0 at both ends)
};

// λ for uniformly spaced samples (interval `dt` [s]) such that the smoother's gain is 1/2 at
// `cutoff_hz`: for long records the spline acts as the filter 1 / (1 + λ ω⁴ / dt⁻¹).
double smoothingLambdaForCutoff(double dt, double cutoff_hz);

}  // namespace gaitopt
