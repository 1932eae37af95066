#pragma once
// Exact gait gradients against central finite differences, shared by the gait tests.
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "gaitopt/gait/evaluator.hpp"

namespace gaitopt::test {

// One differentiated output: its name, its value in an evaluation, and its exact gradient.
struct GradientOutput {
  std::string name;
  std::function<double(const GaitEvaluation<double>&)> value;
  GaitParameters exact;
};

struct GradientCheck {
  int checked = 0, skipped = 0, failed = 0;
  double worst = 0.0;
  std::string worst_what, failures;
  std::map<std::string, double> worst_by_output;  // by output (constraint entries by group)
  std::map<std::string, int> skipped_by_output;
};

// Central differences with h = 1e-6·max(1, |p_i|) against the exact gradient, for every
// parameter the evaluation reads (Parameterisation::isUsed). An entry whose forward and
// backward one-sided differences disagree by more than 1e-3 (relative to max(1, |FD|)) has a
// branch switch (max/clamp/abs) within ±h: its FD is unreliable, it is skipped and counted.
// The others must satisfy |AD − FD| ≤ tolerance·max(1, |FD|).
inline GradientCheck checkGradient(const GaitEvaluator& ev, const GaitParameters& p,
                                   const std::vector<GradientOutput>& outputs,
                                   const std::function<std::string(const std::string&)>& group_of,
                                   double tolerance = 1e-5) {
  GradientCheck r;
  const Parameterisation& par = ev.options().parameterisation;
  const std::vector<std::string> names = par.names();
  const GaitEvaluation<double> e0 = ev.evaluate(p);
  std::vector<double> v0;
  for (const GradientOutput& o : outputs) v0.push_back(o.value(e0));
  for (int i = 0; i < par.size(); ++i) {
    if (!par.isUsed(i)) continue;
    const double h = 1e-6 * std::max(1.0, std::abs(p(i)));
    GaitParameters pp = p, pm = p;
    pp(i) += h;
    pm(i) -= h;
    const GaitEvaluation<double> ep = ev.evaluate(pp), em = ev.evaluate(pm);
    REQUIRE(ep.failed_level == e0.failed_level);
    REQUIRE(em.failed_level == e0.failed_level);
    for (std::size_t j = 0; j < outputs.size(); ++j) {
      const GradientOutput& o = outputs[j];
      const double vp = o.value(ep), vm = o.value(em);
      const double fd = (vp - vm) / (2.0 * h);
      const double forward = (vp - v0[j]) / h, backward = (v0[j] - vm) / h;
      const double scale = std::max(1.0, std::abs(fd));
      const std::string group = group_of(o.name);
      if (std::abs(forward - backward) > 1e-3 * scale) {
        ++r.skipped;
        ++r.skipped_by_output[group];
        continue;
      }
      ++r.checked;
      const double err = std::abs(o.exact(i) - fd) / scale;
      double& w = r.worst_by_output[group];
      w = std::max(w, err);
      if (err > r.worst) {
        r.worst = err;
        r.worst_what = o.name + " / " + names[i];
      }
      if (err > tolerance && ++r.failed <= 20) {
        std::ostringstream s;
        s.precision(10);
        s << o.name << " / " << names[i] << ": AD " << o.exact(i) << ", FD " << fd << " (fwd "
          << forward << ", bwd " << backward << "), rel err " << err << "\n";
        r.failures += s.str();
      }
    }
  }
  return r;
}

}  // namespace gaitopt::test
