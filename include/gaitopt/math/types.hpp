#pragma once
// Fixed-size Eigen aliases templated on the scalar, so every algorithm runs on double and on
// an automatic-differentiation scalar alike.
#include <Eigen/Core>

namespace gaitopt {

template <class S> using Vector2 = Eigen::Matrix<S, 2, 1>;
template <class S> using Vector4 = Eigen::Matrix<S, 4, 1>;
template <class S> using Vector5 = Eigen::Matrix<S, 5, 1>;
template <class S> using Vector7 = Eigen::Matrix<S, 7, 1>;
template <class S> using Matrix5 = Eigen::Matrix<S, 5, 5>;
template <class S> using Matrix7 = Eigen::Matrix<S, 7, 7>;
template <class S> using Matrix25 = Eigen::Matrix<S, 2, 5>;
template <class S> using Matrix27 = Eigen::Matrix<S, 2, 7>;

// a · b for a constant (double) matrix a and a matrix b of any scalar; skips the structural
// zeros of a (the θ-map and D_Γ are mostly 0 and ±1).
template <class S, int R, int K, int C>
Eigen::Matrix<S, R, C> constantTimes(const Eigen::Matrix<double, R, K>& a,
                                     const Eigen::Matrix<S, K, C>& b) {
  Eigen::Matrix<S, R, C> out;
  for (int i = 0; i < R; ++i)
    for (int j = 0; j < C; ++j) {
      S acc(0.0);
      for (int k = 0; k < K; ++k)
        if (a(i, k) != 0.0) acc += a(i, k) * b(k, j);
      out(i, j) = acc;
    }
  return out;
}

}  // namespace gaitopt
