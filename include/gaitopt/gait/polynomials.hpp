#pragma once
// Virtual-constraint polynomials of the gait. Each is the cubic Hermite interpolant of its end
// values and slopes plus u²(u − h)² q(u), with q the polynomial through the K interior points
// (Newton form): degree 3 + K. K = 1 at α_int is the SS quartic (3.25) of the thesis, K = 0 the
// DS cubics (3.26), (3.27); larger K is the richer parameterisation (higher degrees).
#include <vector>

namespace gaitopt {

template <class S> struct PolyValue {
  S value, first, second;  // p, dp/dx, d²p/dx²
};

// The C¹ smoothstep 3u² − 2u³ of u = (x − x0) / length, 0 before x0 and 1 past x0 + length
// (a negative length: x decreasing), with its x-derivatives: a blend that starts and ends with
// zero slope.
inline PolyValue<double> smoothstep(double x, double x0, double length) {
  const double u = (x - x0) / length;
  if (u <= 0.0) return {0.0, 0.0, 0.0};
  if (u >= 1.0) return {1.0, 0.0, 0.0};
  return {u * u * (3.0 - 2.0 * u), 6.0 * u * (1.0 - u) / length,
          (6.0 - 12.0 * u) / (length * length)};
}

// p(x) = Σ_k c_k (x − x0)^k.
template <class S> struct LocalPolynomial {
  S x0;
  std::vector<S> c;

  PolyValue<S> operator()(const S& x) const {
    const S u = x - x0;
    PolyValue<S> r{S(0.0), S(0.0), S(0.0)};
    for (int k = static_cast<int>(c.size()) - 1; k >= 0; --k) {
      r.second = r.second * u + 2.0 * r.first;
      r.first = r.first * u + r.value;
      r.value = r.value * u + c[k];
    }
    return r;
  }
};

template <class S>
LocalPolynomial<S> cubicHermite(const S& x0, const S& y0, const S& m0, const S& x1, const S& y1,
                                const S& m1) {
  const S h = x1 - x0;
  const S secant = (y1 - y0) / h;
  return {x0, {y0, m0, S((3.0 * secant - 2.0 * m0 - m1) / h),
               S((m0 + m1 - 2.0 * secant) / (h * h))}};
}

// End values/slopes at x0, x1 and values ys at the interior abscissae xs.
template <class S>
LocalPolynomial<S> polynomialThrough(const S& x0, const S& y0, const S& m0, const std::vector<S>& xs,
                                     const std::vector<S>& ys, const S& x1, const S& y1,
                                     const S& m1) {
  LocalPolynomial<S> p = cubicHermite(x0, y0, m0, x1, y1, m1);
  const std::size_t K = xs.size();
  if (K == 0) return p;
  const S h = x1 - x0;
  // Residuals divided by the bump u²(u − h)², then Newton divided differences in u.
  std::vector<S> u(K), a(K);
  for (std::size_t k = 0; k < K; ++k) {
    u[k] = xs[k] - x0;
    const S v = xs[k] - x1;
    a[k] = (ys[k] - p(xs[k]).value) / (u[k] * u[k] * v * v);
  }
  for (std::size_t level = 1; level < K; ++level)
    for (std::size_t k = K - 1; k >= level; --k) a[k] = (a[k] - a[k - 1]) / (u[k] - u[k - level]);
  std::vector<S> q{a[K - 1]};  // Newton form to monomials in u
  for (std::size_t k = K - 1; k-- > 0;) {
    q.push_back(S(0.0));
    for (std::size_t i = q.size() - 1; i > 0; --i) q[i] = q[i - 1] - u[k] * q[i];
    q[0] = a[k] - u[k] * q[0];
  }
  // + u²(u − h)² q(u) = (u⁴ − 2h u³ + h² u²) q(u).
  p.c.resize(q.size() + 4, S(0.0));
  for (std::size_t i = 0; i < q.size(); ++i) {
    p.c[i + 2] += h * h * q[i];
    p.c[i + 3] -= 2.0 * h * q[i];
    p.c[i + 4] += q[i];
  }
  return p;
}

}  // namespace gaitopt
