#pragma once
// The α dynamics of the double support under perfect tracking (§4.2.2.2, H1–H3): the bound
// curves of the finite-time convergence zone S_d (4.15)–(4.16), Theorem 1 as a membership test,
// the time-optimal law (4.1), and the data of Fig. 4.5.
//
// Curves are integrated in α with v = α̇² as state, dv/dα = 2 α̈ (the corrected (4.15): the
// printed integral has the wrong sign and hides an ODE), which stays regular where α̇ → 0;
// α̇ = −√v (H2: α̇ ≤ 0). SUNDIALS CVODE (sim/cvode_integrator.hpp) integrates them and its root
// finding locates α̇ = 0 and the meeting with the cyclic curve; α̈_min/max come from the exact
// LPs of sim/ds_acceleration_bounds.hpp. Curves are labelled by the acceleration generating them
// (digest §7.2 item 11): braking (α̈_max) gives the fastest admissible start, speeding up
// (α̈_min) the slowest.
#include <string>
#include <vector>

#include "gaitopt/control/ds_acceleration_bounds.hpp"

namespace gaitopt {

enum class DsBoundKind {
  Braking,     // α̈ = α̈_max: lower signed boundary of S_d, the fastest start
  SpeedingUp,  // α̈ = α̈_min: upper signed boundary, the slowest start
};

// A curve in the (α, α̇) plane, sampled from its start to where it ended.
struct DsPhaseCurve {
  std::vector<double> alpha, alphad;
  // "alpha_iDS" / "alpha_fDS": reached the end of the DS; "at_rest": α̇ reached 0; "undefined":
  // (4.2) became infeasible (H1 fails there); "on_cycle" (time-optimal law): met the cyclic curve
  // and followed it to α_fDS.
  std::string end;
  double end_alphad = std::numeric_limits<double>::quiet_NaN();  // α̇ where it ended
};

// (4.15), (4.16): integrated backward from (α_fDS, α̇_fDS) to α_iDS with α̈_max or α̈_min.
DsPhaseCurve dsBoundCurve(const Model& model, const GaitMotion<double>& motion,
                          const DsLimits& limits, double alphad_fDS, DsBoundKind kind,
                          int samples = 101);

// S_d for one target α̇_fDS: the two bound curves and α̇ = 0 (§4.2.2.2).
struct DsConvergenceZone {
  double alphad_fDS;
  DsPhaseCurve braking, speeding_up;
  // α̇ bounds at α (linear interpolation between the curves' samples, exact at α_iDS and α_fDS);
  // the slowest is 0 where the speeding-up curve stopped: any slower start down to rest is in.
  double fastest(double alpha) const;
  double slowest(double alpha) const;
  // Theorem 1: (α, α̇) with α̇ ≤ 0 between the curves can reach (α_fDS, α̇_fDS) under (4.2).
  bool contains(double alpha, double alphad) const;
};
DsConvergenceZone dsConvergenceZone(const Model& model, const GaitMotion<double>& motion,
                                    const DsLimits& limits, double alphad_fDS, int samples = 101);

// (4.1): α̈_max when too fast (α̇ < α̇_c(α), α̇ < 0), α̈_min when too slow, α̈_c on the curve.
// From a start in DS, integrated to α_fDS; switching when the state meets the cyclic curve.
DsPhaseCurve runTimeOptimalDs(const Model& model, const GaitMotion<double>& motion,
                              const DsLimits& limits, double alpha_start, double alphad_start,
                              int samples = 101);

// (4.28): α̇_iDS = a(α̇_fDS) = κ α̇_fSS, α̇_fSS = −√(Φ(α_fSS) + f(α_iSS)² α̇_fDS²) / f(α_fSS) (4.17)
// with α̇_iSS = α̇_fDS, from the gait's SS zero dynamics (Φ at the SS nodes, κ the exchange or
// impact rate ratio). NaN when the SS falls back (Φ + f_i² α̇² ≤ 0 at a node: below the SS
// admissibility bound α̇_fDS,minSS).
double zeroDynamicsStepMap(const GaitMotion<double>& motion, double alphad_fDS);

// Fig. 4.5 and Theorems 1–3 for the gait: the zone's ends at α_iDS and a over a grid of α̇_fDS,
// and the cycle's place in its own zone.
struct DsZoneRow {
  double alphad_fDS;
  double fastest_iDS, slowest_iDS;  // α̇_iDS,min / α̇_iDS,max of §4.2.2.3 (signed: fastest < slowest)
  std::string braking_end, speeding_up_end;
  double a;  // (4.28)
  // Theorem 3: a cyclic motion with this α̇_fDS exists (a in [fastest, slowest]); strictly inside
  // (Theorem 4): locally stable with one-step convergence. The SS upper bound (torque and
  // contact limits in SS, α̇_fDS,maxSS) is not checked.
  bool cycle_exists, cycle_stable;
};
struct DsZoneStudy {
  double alpha_iDS, alpha_fDS;
  double cycle_alphad_iDS, cycle_alphad_fDS;  // the gait's cyclic DS ends
  DsZoneRow cycle;  // the zone of the cycle's α̇_fDS
  // Theorem 2's premise: min over the cyclic DS of α̈_max − α̈_c and α̈_c − α̈_min (≥ 0: the
  // reference satisfies (4.2)); at `cycle_margin_samples` points of α.
  double cycle_braking_margin, cycle_speeding_up_margin;
  int cycle_margin_samples;
  bool cycle_in_zone;         // Theorem 3 for the cycle: α̇_c,iDS in [fastest, slowest]
  bool cycle_strictly_inside;  // Theorem 4: one-step convergence around it
  DsPhaseCurve from_rest;      // (4.1) from (α_iDS, 0) (Fig. 4.1)
  std::vector<DsZoneRow> rows;
  // The grid interval of α̇_fDS around the cycle's whose rows all have cycle_exists: the family
  // of cyclic motions of Theorem 3 (NaN if the cycle's nearest row has none).
  double existence_low, existence_high;
};
DsZoneStudy studyDsZone(const Model& model, const GaitMotion<double>& motion,
                        const DsLimits& limits, const std::vector<double>& alphad_fDS_grid);

}  // namespace gaitopt
