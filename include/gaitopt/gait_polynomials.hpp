#pragma once
// Virtual-constraint polynomials of the gait: cubic Hermite segments (DS δ1(α), δ2(α) (3.26) and
// α(t) (3.27)) and the SS quartics (3.25). The quartic with end values/slopes and one interior
// value is the end-point Hermite cubic plus c (x − x0)²(x − x1)², the closed-form solution of
// the 5×5 system (3.25).
#include <array>

namespace gaitopt {

template <class S> struct PolyValue {
  S value, first, second;  // p, dp/dx, d²p/dx²
};

// p(x) = Σ_k c_k (x − x0)^k, k ≤ 4.
template <class S> struct LocalQuartic {
  S x0;
  std::array<S, 5> c;

  PolyValue<S> operator()(const S& x) const {
    const S u = x - x0;
    PolyValue<S> r;
    r.value = (((c[4] * u + c[3]) * u + c[2]) * u + c[1]) * u + c[0];
    r.first = ((4.0 * c[4] * u + 3.0 * c[3]) * u + 2.0 * c[2]) * u + c[1];
    r.second = (12.0 * c[4] * u + 6.0 * c[3]) * u + 2.0 * c[2];
    return r;
  }
};

template <class S>
LocalQuartic<S> cubicHermite(const S& x0, const S& y0, const S& m0, const S& x1, const S& y1,
                             const S& m1) {
  const S h = x1 - x0;
  const S secant = (y1 - y0) / h;
  LocalQuartic<S> p;
  p.x0 = x0;
  p.c = {y0, m0, (3.0 * secant - 2.0 * m0 - m1) / h, (m0 + m1 - 2.0 * secant) / (h * h), S(0.0)};
  return p;
}

// (3.25): values and slopes at x0, x1 and the value y_int at x_int.
template <class S>
LocalQuartic<S> quarticThrough(const S& x0, const S& y0, const S& m0, const S& x_int,
                               const S& y_int, const S& x1, const S& y1, const S& m1) {
  LocalQuartic<S> p = cubicHermite(x0, y0, m0, x1, y1, m1);
  const S h = x1 - x0, ui = x_int - x0, vi = x_int - x1;
  const S bump = (y_int - p(x_int).value) / (ui * ui * vi * vi);
  p.c[2] += bump * h * h;
  p.c[3] -= 2.0 * bump * h;
  p.c[4] = bump;
  return p;
}

}  // namespace gaitopt
