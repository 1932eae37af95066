#pragma once
// The gait parameters. Miossec's 17 (§3.2.1.4 with θ3 and T_DS, digest §3.4) come first, in
// the order and with the YAML names of the project (radians, metres, seconds; `delta*s_*` are
// ∂δ/∂α). A richer parameterisation appends interior configurations of the virtual
// constraints: each extra SS point (δ1, θ3, x2r, z2 at a fixed fraction of the SS α range)
// raises the SS polynomials' degree by one, each DS point (δ1, θ3 at a fraction of the DS α
// range) the DS polynomials' degree (gait/polynomials.hpp). Extra SS points carry joint angles
// (δ1, θ3, δ3, δ4) rather than the α_int point's swing-foot position, so they need no inverse
// kinematics and any step refines into them exactly (a foot position loses the knee branch).
// A gait landing with an impact appends the two SS-end slopes δ3*, δ4* (gait/impact_landing.hpp).
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace gaitopt {

constexpr int kNumGaitParameters = 17;   // the thesis' set
constexpr int kMaxGaitParameters = 64;   // richest parameterisation supported

enum GaitParameter : int {
  kAlphaIDS = 0,   // front tibia angle at DS start
  kDelta1IDS,      // front knee at DS start
  kTheta3IDS,      // absolute trunk angle at DS start
  kStepLength,     // d: distance between the feet in DS
  kAlphaFDS,       // DS end (= SS start)
  kDelta1FDS,
  kTheta3FDS,
  kDelta1Int,      // SS configuration at α_int = (α_iSS + α_fSS)/2
  kTheta3Int,
  kX2rInt,         // swing foot x relative to the hip at α_int
  kZ2Int,          // swing foot height at α_int
  kAlphadotISS,    // initial condition of the zero dynamics (< 0)
  kDelta1sISS,     // ∂δ1/∂α at SS start
  kDelta2sISS,
  kDelta1sFSS,     // ∂δ1/∂α at SS end
  kDelta2sFSS,
  kTDS,            // double-support duration
};

extern const std::array<const char*, kNumGaitParameters> kGaitParameterNames;

// How the swing foot lands at the end of the single support.
enum class Landing {
  ZeroVelocity,           // the thesis: δ3*, δ4* at SS end from zero foot-2 velocity (3.20)
  ImpactSingleSupport,    // impact, then single support on the new leg (foot 1 lifts)
  ImpactDoubleSupport,    // impact, then double support (both feet stick)
};

// How the virtual constraints pass through their end values, end slopes and interior points
// (gait/path_curve.hpp).
enum class PathBasis {
  Polynomial,  // one polynomial of degree 3 + K (the thesis for K = 1)
  BSpline,     // C² cubic B-spline with a knot at each interior point (K + 4 control points)
};

struct Parameterisation {
  // Interior SS configurations at α fractions k/(ss_points+1) of [α_iSS → α_fSS]; odd, so the
  // middle one is the thesis' α_int (parameters 7–10). 1 = the thesis (quartics).
  int ss_points = 1;
  // Interior DS configurations at α fractions k/(ds_points+1) of [α_iDS → α_fDS]; 0 = the
  // thesis (cubics).
  int ds_points = 0;
  Landing landing = Landing::ZeroVelocity;
  PathBasis basis = PathBasis::Polynomial;  // of the SS and DS virtual constraints

  int size() const { return impactSlopeIndex() + (landsWithImpact() ? 2 : 0); }
  bool isThesis() const {
    return ss_points == 1 && ds_points == 0 && !landsWithImpact() && basis == PathBasis::Polynomial;
  }
  bool landsWithImpact() const { return landing != Landing::ZeroVelocity; }
  bool hasDoubleSupport() const { return landing != Landing::ImpactSingleSupport; }
  // First of the SS-end slopes δ3*, δ4* of a landing with impact (free: the foot arrives
  // with a non-zero velocity).
  int impactSlopeIndex() const { return kNumGaitParameters + 4 * (ss_points - 1) + 2 * ds_points; }
  // Whether parameter i enters the evaluation. An impact followed by single support has no
  // double support: the SS starts at the post-impact configuration (α_iDS, δ1_iDS, θ3_iDS)
  // with the post-impact velocity, so α_fDS, δ1_fDS, θ3_fDS, T_DS, α̇_iSS, δ1*_iSS and δ2*_iSS
  // are determined by the impact and cyclicity, not free.
  bool isUsed(int i) const;
  double ssFraction(int k) const { return (k + 1.0) / (ss_points + 1.0); }
  double dsFraction(int k) const { return (k + 1.0) / (ds_points + 1.0); }
  // First of the 4 parameters of SS point k (0 ≤ k < ss_points): (δ1, θ3, x2r, z2) for the
  // middle point α_int, (δ1, θ3, δ3, δ4) for the others.
  int ssPointIndex(int k) const;
  bool isFootPoint(int k) const { return k == ss_points / 2; }
  // First of the 2 parameters (δ1, θ3) of DS point k.
  int dsPointIndex(int k) const;
  std::vector<std::string> names() const;
  std::string label() const;  // "miossec", "miossec+ss3+ds1", "miossec+impact_ss", "…+bspline"
  bool operator==(const Parameterisation& o) const {
    return ss_points == o.ss_points && ds_points == o.ds_points && landing == o.landing &&
           basis == o.basis;
  }
};

template <class S>
using GaitVector = Eigen::Matrix<S, Eigen::Dynamic, 1, 0, kMaxGaitParameters, 1>;
using GaitParameters = GaitVector<double>;

// A per-parameter quantity (bound, scale, half-width) of the thesis' 17 extended to `par`: each
// extra SS point takes δ1, θ3 of the α_int point (entries 7–8) and `ss_joints` for δ3, δ4,
// each DS point `ds` (for δ1, θ3).
GaitParameters extendPerParameter(const GaitParameters& thesis17, const Parameterisation& par,
                                  const std::array<double, 2>& ss_joints,
                                  const std::array<double, 2>& ds);

}  // namespace gaitopt
