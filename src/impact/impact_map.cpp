#include "gaitopt/impact/impact_map.hpp"

#include <algorithm>
#include <cmath>

#include "gaitopt/model/dynamics_pinned.hpp"

namespace gaitopt {

Vec5 pinnedVelocityForFoot2(const Model& model, const Vec5& q, const Vec2& v2) {
  const PinnedTerms<double> t = pinnedTerms(model, q, Vec5(Vec5::Zero()));
  return t.D2.transpose() * (t.D2 * t.D2.transpose()).ldlt().solve(v2);
}

std::string behaviourLabel(ImpactBehaviour b) {
  return std::string(toString(b.foot1)) + "/" + toString(b.foot2);
}

namespace {

double sample(double a, double b, int n, int i) {
  return n <= 1 ? a : a + (b - a) * static_cast<double>(i) / static_cast<double>(n - 1);
}

// Impact system for V2⁻ = v2 at configuration q.
ImpactSystem<double> systemFor(const Model& model, const Vec5& q, const Vec2& v2) {
  Vector7<double> X, Xd;
  floatingStateFromPinned(model, q, pinnedVelocityForFoot2(model, q, v2), X, Xd);
  return impactSystem(model, X, Xd);
}

}  // namespace

std::vector<ThetaInterval> algebraicThetaIntervals(const Model& model, const Vec5& q, double mu,
                                                   double theta_min, double theta_max) {
  const ImpactSystem<double> sc = systemFor(model, q, Vec2(1.0, 0.0));
  const ImpactSystem<double> ss = systemFor(model, q, Vec2(0.0, 1.0));
  std::vector<ThetaInterval> out;
  for (ImpactBehaviour b : allImpactBehaviours()) {
    // Slacks are linear in V⁻: s(θ) = a cos θ + b sin θ.
    const Eigen::VectorXd a = algebraicImpact(sc, b, mu).slacks;
    const Eigen::VectorXd s = algebraicImpact(ss, b, mu).slacks;
    if (!a.allFinite() || !s.allFinite()) continue;
    std::vector<double> cuts{theta_min, theta_max};
    for (Eigen::Index k = 0; k < a.size(); ++k) {
      const double zero = std::atan2(-a(k), s(k));  // a cos + b sin = 0, and its antipode
      for (double z : {zero - 2.0 * M_PI, zero - M_PI, zero, zero + M_PI})
        if (z > theta_min && z < theta_max) cuts.push_back(z);
    }
    std::sort(cuts.begin(), cuts.end());
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      const double mid = 0.5 * (cuts[i] + cuts[i + 1]);
      const Eigen::VectorXd v = a * std::cos(mid) + s * std::sin(mid);
      if (cuts[i + 1] <= cuts[i] || v.minCoeff() < 0.0) continue;
      if (!out.empty() && out.back().behaviour == b && out.back().end == cuts[i])
        out.back().end = cuts[i + 1];
      else
        out.push_back({b, cuts[i], cuts[i + 1]});
    }
  }
  return out;
}

std::vector<ImpactMapRow> impactMap(const Model& model, const Vec5& q, const ImpactMapRequest& r) {
  std::vector<ImpactMapRow> rows;
  for (int i = 0; i < r.mu_count; ++i) {
    const double mu = sample(r.mu_min, r.mu_max, r.mu_count, i);
    ImpactOptions options = r.options;
    options.mu = mu;
    std::vector<ThetaInterval> intervals;
    if (r.model == ImpactModelKind::Algebraic)
      intervals = algebraicThetaIntervals(model, q, mu, r.theta_min, r.theta_max);
    for (int j = 0; j < r.theta_count; ++j) {
      ImpactMapRow row;
      row.theta = sample(r.theta_min, r.theta_max, r.theta_count, j);
      row.mu = mu;
      if (r.model == ImpactModelKind::Algebraic) {
        for (const ThetaInterval& iv : intervals)
          if (row.theta >= iv.begin && row.theta <= iv.end) row.behaviours.push_back(iv.behaviour);
        row.status = row.behaviours.empty()     ? ImpactStatus::Inconsistent
                     : row.behaviours.size() > 1 ? ImpactStatus::Indeterminate
                                                 : ImpactStatus::Unique;
      } else {
        const ImpactResult res = solveDifferentialImpact(
            systemFor(model, q, Vec2(std::cos(row.theta), std::sin(row.theta))), options);
        for (const ImpactSolution& s : res.solutions) row.behaviours.push_back(s.contact);
        row.status = res.status;
      }
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

}  // namespace gaitopt
