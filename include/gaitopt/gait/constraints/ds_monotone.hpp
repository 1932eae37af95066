#pragma once
// Monotone DS (3.43): the stance-leg angle α keeps moving forward, α̇ ≤ α̇_max < 0.
#include "gaitopt/gait/constraints/group_spec.hpp"

namespace gaitopt {

template <class S> S dsMonotoneRow(const S& alphadot, double alphadot_max) {
  return alphadot - alphadot_max;
}

constexpr ConstraintGroupSpec kDsMonotoneSpec{"ds_monotone", 5, "(3.43)", "rad/s",
                                              dimensionlessScale, ConstraintPhase::DoubleSupport};

}  // namespace gaitopt
