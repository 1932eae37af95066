#pragma once
// Thin RAII adapter over SUNDIALS CVODE (6.x): variable-order Adams–Moulton with fixed-point
// iteration for the smooth, non-stiff walking dynamics, and CVODE's root finding on the dense
// output, which locates hybrid events to round-off (far below 1e-9 s). Chosen over
// Boost.Odeint because root finding is built in and CVODES adds forward sensitivities for the
// Poincaré Jacobian with the same interface.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

namespace gaitopt {

// CVODE could not continue an integration (e.g. its step limit between two outputs, or an
// error test failing at the minimum step): the time reached and CVODE's own message.
class IntegrationError : public std::runtime_error {
 public:
  IntegrationError(double t, const std::string& message) : std::runtime_error(message), t_(t) {}
  double time() const { return t_; }

 private:
  double t_;
};

struct CvodeTolerances {
  double relative = 1e-10;
  double absolute = 1e-12;
  Eigen::VectorXd absolute_per_component;  // if not empty: replaces `absolute`
};

class CvodeIntegrator {
 public:
  using Rhs = std::function<void(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot)>;
  using Roots = std::function<void(double t, const Eigen::VectorXd& y, Eigen::VectorXd& g)>;

  // `roots` returns `n_roots` event functions; an event is a crossing of one of them from
  // positive to negative.
  CvodeIntegrator(int n, const Rhs& rhs, int n_roots, const Roots& roots,
                  const CvodeTolerances& tol = {});
  ~CvodeIntegrator();
  CvodeIntegrator(const CvodeIntegrator&) = delete;
  CvodeIntegrator& operator=(const CvodeIntegrator&) = delete;

  // Restarts at (t0, y0) (after an event map).
  void reset(double t0, const Eigen::VectorXd& y0);

  struct Result {
    double t;
    Eigen::VectorXd y;
    int root = -1;  // index of the event function that vanished, −1 if t_end was reached
  };
  // Integrates until an event or t_end (the state there interpolated on CVODE's dense output,
  // so output times do not shorten the steps); throws std::runtime_error if CVODE fails.
  Result advance(double t_end);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gaitopt
