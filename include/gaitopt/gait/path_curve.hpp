#pragma once
// A virtual constraint δ_j(α) (3.2), (3.3) as a piecewise polynomial: one piece for the
// polynomial basis (gait/polynomials.hpp), one cubic per interval between interpolation points
// for the B-spline basis (gait/cubic_spline.hpp). The evaluator, the trajectory and the
// simulators call it like a polynomial; the pieces are exposed for the controller export.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "gaitopt/gait/cubic_spline.hpp"
#include "gaitopt/gait/parameters.hpp"
#include "gaitopt/gait/polynomials.hpp"
#include "gaitopt/math/scalar.hpp"

namespace gaitopt {

template <class S> struct PathCurve {
  // pieces[i] holds between breaks[i] and breaks[i + 1] (breaks.size() = pieces.size() + 1);
  // the breaks run from the curve's start to its end, increasing or decreasing.
  std::vector<LocalPolynomial<S>> pieces;
  std::vector<S> breaks;

  PathCurve() = default;
  PathCurve(LocalPolynomial<S> p, const S& x_begin, const S& x_end)
      : pieces{std::move(p)}, breaks{x_begin, x_end} {}

  PolyValue<S> operator()(const S& x) const { return pieces[pieceOf(valueOf(x))](x); }

  // The single polynomial of a one-piece curve (the controller export writes monomials).
  const LocalPolynomial<S>& polynomial() const {
    if (pieces.size() != 1)
      throw std::invalid_argument("the virtual constraint is a B-spline of " +
                                  std::to_string(pieces.size()) +
                                  " pieces, not one polynomial (parameterisation basis: "
                                  "polynomial is needed here)");
    return pieces.front();
  }

 private:
  // Piece whose interval holds x; outside the curve's range, the first or last piece extends it.
  std::size_t pieceOf(double x) const {
    const double x0 = valueOf(breaks.front()), span = valueOf(breaks.back()) - x0;
    std::size_t i = 0;
    while (i + 1 < pieces.size() && (x - valueOf(breaks[i + 1])) / span > 0.0) ++i;
    return i;
  }
};

// The curve of `basis` with end values/slopes at x0, x1 and values ys at the interior
// abscissae xs (the same data for both bases, so a gait's parameters mean the same points).
template <class S>
PathCurve<S> pathThrough(PathBasis basis, const S& x0, const S& y0, const S& m0,
                         const std::vector<S>& xs, const std::vector<S>& ys, const S& x1,
                         const S& y1, const S& m1) {
  if (basis == PathBasis::Polynomial)
    return PathCurve<S>(polynomialThrough(x0, y0, m0, xs, ys, x1, y1, m1), x0, x1);
  PathCurve<S> c;
  c.breaks.push_back(x0);
  c.breaks.insert(c.breaks.end(), xs.begin(), xs.end());
  c.breaks.push_back(x1);
  std::vector<S> values{y0};
  values.insert(values.end(), ys.begin(), ys.end());
  values.push_back(y1);
  c.pieces = cubicSplinePieces(c.breaks, values, m0, m1);
  return c;
}

}  // namespace gaitopt
