#pragma once
// Interpolating C² cubic spline with clamped ends: through (x_i, y_i), i = 0..N−1 (x monotone,
// increasing or decreasing), with slopes m_first at x_0 and m_last at x_{N−1}. It is the cubic
// B-spline with a knot at every interior x_i (N + 2 control points), written here as N − 1
// cubic Hermite pieces. The interior slopes solve the C² conditions, a strictly diagonally
// dominant tridiagonal system (Thomas elimination: stable without pivoting, and free of
// branches on the scalar, so an AD scalar gets the exact derivatives). It reproduces every
// cubic exactly.
#include <vector>

#include "gaitopt/gait/polynomials.hpp"

namespace gaitopt {

template <class S>
std::vector<LocalPolynomial<S>> cubicSplinePieces(const std::vector<S>& x, const std::vector<S>& y,
                                                  const S& m_first, const S& m_last) {
  const std::size_t n = x.size();
  std::vector<S> h(n - 1), secant(n - 1), m(n, S(0.0));
  for (std::size_t i = 0; i + 1 < n; ++i) {
    h[i] = x[i + 1] - x[i];
    secant[i] = (y[i + 1] - y[i]) / h[i];
  }
  m[0] = m_first;
  m[n - 1] = m_last;
  // Row i (1 ≤ i ≤ n−2): h_i m_{i−1} + 2(h_{i−1} + h_i) m_i + h_{i−1} m_{i+1}
  //                      = 3 (h_i s_{i−1} + h_{i−1} s_i)  (second derivatives continuous).
  std::vector<S> diag(n, S(0.0)), rhs(n, S(0.0));
  for (std::size_t i = 1; i + 1 < n; ++i) {
    diag[i] = 2.0 * (h[i - 1] + h[i]);
    rhs[i] = 3.0 * (h[i] * secant[i - 1] + h[i - 1] * secant[i]);
  }
  if (n > 2) {
    rhs[1] -= h[1] * m[0];
    rhs[n - 2] -= h[n - 3] * m[n - 1];
  }
  for (std::size_t i = 2; i + 1 < n; ++i) {  // forward elimination of the sub-diagonal h_i
    const S f = h[i] / diag[i - 1];
    diag[i] -= f * h[i - 2];
    rhs[i] -= f * rhs[i - 1];
  }
  for (std::size_t i = n - 2; i >= 1 && i + 1 < n; --i)  // back substitution (super-diagonal h_{i−1})
    m[i] = (rhs[i] - (i + 2 < n ? S(h[i - 1] * m[i + 1]) : S(0.0))) / diag[i];
  std::vector<LocalPolynomial<S>> pieces;
  for (std::size_t i = 0; i + 1 < n; ++i)
    pieces.push_back(cubicHermite(x[i], y[i], m[i], x[i + 1], y[i + 1], m[i + 1]));
  return pieces;
}

}  // namespace gaitopt
