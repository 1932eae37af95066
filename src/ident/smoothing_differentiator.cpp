#include "gaitopt/ident/smoothing_differentiator.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace gaitopt {

std::vector<Segment> dataSegments(const MeasuredData& d) {
  std::vector<Segment> out;
  for (std::size_t i = 0; i < d.size();) {
    Segment s{i, i, d.phase[i], d.stance[i], d.step[i]};
    while (s.end < d.size() && d.phase[s.end] == s.phase && d.stance[s.end] == s.stance &&
           d.step[s.end] == s.step)
      ++s.end;
    out.push_back(s);
    i = s.end;
  }
  return out;
}

SmoothingDifferentiator::SmoothingDifferentiator(const std::vector<double>& t,
                                                 const std::vector<Segment>& segments,
                                                 double half_window, int order)
    : rows_(t.size()), half_window_(half_window), order_(order) {
  std::map<std::tuple<int, int, long long>, Eigen::Matrix<double, 3, Eigen::Dynamic>> cache;
  for (const Segment& s : segments) {
    for (std::size_t i = s.begin; i < s.end; ++i) {
      std::size_t a = i, b = i + 1;  // window [a, b)
      while (a > s.begin && t[i] - t[a - 1] <= half_window) --a;
      while (b < s.end && t[b] - t[i] <= half_window) ++b;
      // Slide inward at the ends so the window keeps about its full width.
      while (b < s.end && t[b] - t[a] <= 2.0 * half_window) ++b;
      while (a > s.begin && t[b - 1] - t[a - 1] <= 2.0 * half_window) --a;
      const int n = static_cast<int>(b - a);
      // A short segment (a 40 ms double support) gets a lower degree: a degree-8 fit through
      // 18 quantised samples would amplify their noise hugely.
      const int p = std::min(order, std::max(2, n / 5));
      // Uniformly sampled windows of the same shape share their weights.
      bool uniform = n >= 2;
      const double dt = n >= 2 ? t[a + 1] - t[a] : 0.0;
      for (std::size_t k = a + 1; uniform && k < b; ++k)
        uniform = std::abs(t[k] - t[k - 1] - dt) < 1e-9 * std::max(1.0, std::abs(t[k]));
      const std::tuple<int, int, long long> key{n, static_cast<int>(i - a), std::llround(dt * 1e12)};
      if (uniform) {
        const auto hit = cache.find(key);
        if (hit != cache.end()) {
          rows_[i] = {a, hit->second};
          continue;
        }
      }
      Eigen::MatrixXd V(n, p + 1);
      for (int k = 0; k < n; ++k) {
        const double x = (t[a + k] - t[i]) / half_window;  // scaled for conditioning
        double xm = 1.0;
        for (int m = 0; m <= p; ++m, xm *= x) V(k, m) = xm;
      }
      // Least squares by thin QR: coefficients c = R⁻¹ Qᵀ x; only c0..c2 are needed.
      const Eigen::HouseholderQR<Eigen::MatrixXd> qr(V);
      const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(n, p + 1);
      const Eigen::MatrixXd R_inv = qr.matrixQR()
                                        .topLeftCorner(p + 1, p + 1)
                                        .triangularView<Eigen::Upper>()
                                        .solve(Eigen::MatrixXd::Identity(p + 1, p + 1));
      const int rows = std::min(3, p + 1);
      const Eigen::MatrixXd pinv = R_inv.topRows(rows) * Q.transpose();
      Weights& r = rows_[i];
      r.first = a;
      r.w = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, n);
      r.w.row(0) = pinv.row(0);
      if (p >= 1) r.w.row(1) = pinv.row(1) / half_window;
      if (p >= 2) r.w.row(2) = 2.0 * pinv.row(2) / (half_window * half_window);
      if (uniform) cache.emplace(key, r.w);
    }
  }
}

SmoothedSignal SmoothingDifferentiator::apply(const std::vector<double>& x) const {
  SmoothedSignal s;
  s.value.resize(x.size());
  s.first.resize(x.size());
  s.second.resize(x.size());
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    const Weights& r = rows_[i];
    const Eigen::Map<const Eigen::VectorXd> window(x.data() + r.first, r.w.cols());
    const Eigen::Vector3d v = r.w * window;
    s.value[i] = v(0);
    s.first[i] = v(1);
    s.second[i] = v(2);
  }
  return s;
}

Kinematics differentiate(const SmoothingDifferentiator& d, const std::vector<Vec5>& q) {
  Kinematics k;
  k.q.resize(q.size());
  k.qd.resize(q.size());
  k.qdd.resize(q.size());
  std::vector<double> x(q.size());
  for (int c = 0; c < 5; ++c) {
    for (std::size_t i = 0; i < q.size(); ++i) x[i] = q[i](c);
    const SmoothedSignal s = d.apply(x);
    for (std::size_t i = 0; i < q.size(); ++i) {
      k.q[i](c) = s.value[i];
      k.qd[i](c) = s.first[i];
      k.qdd[i](c) = s.second[i];
    }
  }
  return k;
}

}  // namespace gaitopt
