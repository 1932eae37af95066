#pragma once
// What the impact solvers return: every consistent solution with its status, never a silently
// chosen one (digest §1.3, App. B).
#include <string>
#include <vector>

#include "gaitopt/impact/algebraic_impact_equations.hpp"

namespace gaitopt {

enum class ImpactModelKind { Algebraic, Differential };
const char* toString(ImpactModelKind k);  // algebraic | differential

// unique: one solution; indeterminate: several; inconsistent: none; accumulation: one
// solution reached through an infinite, summed sequence of phases (differential model).
enum class ImpactStatus { Unique, Indeterminate, Inconsistent, Accumulation };
const char* toString(ImpactStatus s);

struct ImpactOptions {
  double mu = 0.7;  // Coulomb friction coefficient f
  // Relative tolerance of every zero test. Slacks and velocities are made dimensionless by the
  // arriving speed |V2⁻| (velocities) and by |V2⁻| / max_i W_ii (impulses); a dimensionless
  // value within ±tolerance counts as 0: a slack there is a boundary, a velocity there is at
  // rest. 1e-9 sits well above the ~1e-15 round-off of the 4×4 solves and far below any
  // physically meaningful margin.
  double tolerance = 1e-9;
  // Two solutions whose impulses agree within this fraction of their size are one outcome
  // (a long phase sequence accumulates round-off well above the 4×4 solves' 1e-15).
  double outcome_tolerance = 1e-7;
  int max_phases = 200;    // differential: phases per branch before giving up ("capped")
  int max_branches = 64;   // differential: indeterminate phases branch at most this often
  int max_cycle_length = 8;  // differential: longest repeated phase pattern looked for
};

// One phase of the differential model (the single behaviour for the algebraic one).
struct ImpactPhase {
  ImpactBehaviour behaviour;
  double tau_end;  // normal impulse at foot 2 at the end of the phase [N·s]
};

struct ImpactSolution {
  ImpactBehaviour behaviour;  // algebraic: the behaviour; differential: the last phase's
  ImpactBehaviour contact;    // post-impact contact state read from the final velocities
  bool boundary = false;      // some inequality within tolerance of 0 (zone boundary)
  Vector7<double> Xd_plus;
  Vec2 impulse1, impulse2;
  Eigen::Vector4d V_plus;
  double energy_loss = 0.0;
  std::vector<ImpactPhase> phases;
  // Differential model: the repeated phase pattern whose geometric series was summed.
  bool accumulation = false;
  int accumulation_cycle_length = 0;
};

struct ImpactResult {
  ImpactModelKind model = ImpactModelKind::Algebraic;
  double mu = 0.0;
  Vec2 V2_minus = Vec2::Zero();
  ImpactStatus status = ImpactStatus::Inconsistent;
  std::vector<ImpactSolution> solutions;
  std::vector<std::string> notes;  // e.g. branches found inconsistent, capped sequences
};

// Contact state read from post-impact foot velocities V = [V1; V2] (zero test of
// ImpactOptions::tolerance relative to `speed`).
ImpactBehaviour contactState(const Eigen::Vector4d& V, double speed, double tolerance);

// How both solvers build and classify their solutions.
namespace detail {
// Dimensionless scales of the zero tests: velocity scale |V2⁻|, impulse scale |V2⁻| / max W_ii.
struct ImpactScales {
  double speed, impulse;
};
ImpactScales impactScales(const ImpactSystem<double>& system);
// Post-impact floating velocities, energy loss and contact state of total impulses I.
void completeSolution(const ImpactSystem<double>& system, const Eigen::Vector4d& I,
                      const ImpactOptions& options, ImpactSolution& solution);
// Whether two solutions have the same impulses: within `impulse_tolerance` or, for large
// impulses, within the same tolerance relative to their size.
bool sameOutcome(const ImpactSolution& a, const ImpactSolution& b, double impulse_tolerance,
                 double relative_tolerance);
// Algebraic model: appends `s` unless a solution with the same outcome is already there; a
// merged duplicate marks the kept one as boundary (two behaviours meeting at a zone edge).
void addDistinctSolution(std::vector<ImpactSolution>& solutions, ImpactSolution s,
                         double impulse_tolerance, double relative_tolerance);
// inconsistent: no solution; indeterminate: at least two different outcomes; otherwise
// accumulation when some solution went through a summed accumulation, else unique.
ImpactStatus statusOf(const std::vector<ImpactSolution>& solutions, double impulse_tolerance,
                      double relative_tolerance);
}  // namespace detail

}  // namespace gaitopt
