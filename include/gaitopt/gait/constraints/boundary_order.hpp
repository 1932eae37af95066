#pragma once
// Order of the boundary configurations (3.38) and the tibiae's orientation (3.40), on the
// stance-leg angle α: the DS covers at least a minimal range, the SS moves α forward, and
// neither tibia passes the horizontal.
#include <cmath>

#include "gaitopt/gait/constraints/group_spec.hpp"

namespace gaitopt {

// (3.38): α_fDS − α_iDS ≤ −range_min.
template <class S> S alphaOrderDsRow(const S& alpha_iDS, const S& alpha_fDS, double range_min) {
  return alpha_fDS - alpha_iDS + range_min;
}
// (3.38): α_fSS ≤ α_fDS − margin (α_iSS = α_fDS).
template <class S> S alphaOrderSsRow(const S& alpha_fDS, const S& alpha_fSS, double margin) {
  return alpha_fSS - alpha_fDS + margin;
}
// (3.40): the front tibia at α_iDS and the rear one at α_fSS short of the horizontal.
template <class S> S tibiaFrontRow(const S& alpha_iDS, double margin) {
  return alpha_iDS - 0.5 * M_PI + margin;
}
template <class S> S tibiaRearRow(const S& alpha_fSS, double margin) {
  return -0.5 * M_PI - alpha_fSS + margin;
}

constexpr ConstraintGroupSpec kAlphaOrderDsSpec{"alpha_order_DS", 1, "(3.38)", "rad",
    dimensionlessScale, ConstraintPhase::None, 1, 0, ConstraintPresence::WithDoubleSupport};
constexpr ConstraintGroupSpec kAlphaOrderSsSpec{"alpha_order_fDS_fSS", 1, "(3.38)", "rad",
                                                dimensionlessScale};
constexpr ConstraintGroupSpec kTibiaFrontSpec{"tibia_front", 1, "(3.40)", "rad",
                                              dimensionlessScale};
constexpr ConstraintGroupSpec kTibiaRearSpec{"tibia_rear", 1, "(3.40)", "rad", dimensionlessScale};

}  // namespace gaitopt
