#pragma once
// Small helpers that let templated code treat double and Eigen::AutoDiffScalar uniformly:
// read the plain value (for branching / searching, never for the result), build constants,
// and pick the result type of an operation that mixes a double with an AD scalar.
#include <type_traits>

#include <Eigen/Core>  // must precede the AutoDiff module, which does not include it itself
#include <unsupported/Eigen/AutoDiff>

namespace gaitopt {

// Plain value of a double; the base case of the recursion below.
inline double valueOf(double x) { return x; }

// Plain value of an AD scalar (recurses, so nested AD for second derivatives works too); use it
// only for decisions (comparisons, index searches) so no derivative information is dropped.
template <class DerType>
double valueOf(const Eigen::AutoDiffScalar<DerType>& x) {
  return valueOf(x.value());
}

// A constant of scalar type S (zero derivatives for AD types); spelled out so intent is clear.
template <class S>
S cast(double x) {
  return S(x);
}

// Result type when a quantity of type A meets one of type B, where each is a built-in
// arithmetic type (double, int, ...) or one AD type: the AD type wins, plain numbers give double.
// Two different AD types are not supported.
template <class A, class B>
struct PromoteScalar {
  static_assert(std::is_arithmetic<A>::value || std::is_arithmetic<B>::value ||
                    std::is_same<A, B>::value,
                "PromoteScalar: mixing two different AD scalar types is not supported");
  using type = std::conditional_t<
      std::is_arithmetic<A>::value,
      std::conditional_t<std::is_arithmetic<B>::value, double, B>, A>;
};
template <class A, class B>
using PromoteScalarT = typename PromoteScalar<std::decay_t<A>, std::decay_t<B>>::type;

}  // namespace gaitopt
