#include "gaitopt/gait/parameters.hpp"

namespace gaitopt {

const std::array<const char*, kNumGaitParameters> kGaitParameterNames = {
    "alpha_iDS",   "delta1_iDS",   "theta3_iDS",   "d",           "alpha_fDS",   "delta1_fDS",
    "theta3_fDS",  "delta1_int",   "theta3_int",   "x2r_int",     "z2_int",      "alphadot_iSS",
    "delta1s_iSS", "delta2s_iSS",  "delta1s_fSS",  "delta2s_fSS", "T_DS"};

int Parameterisation::ssPointIndex(int k) const {
  const int middle = ss_points / 2;
  if (k == middle) return kDelta1Int;
  return kNumGaitParameters + 4 * (k < middle ? k : k - 1);
}

int Parameterisation::dsPointIndex(int k) const {
  return kNumGaitParameters + 4 * (ss_points - 1) + 2 * k;
}

std::vector<std::string> Parameterisation::names() const {
  std::vector<std::string> n(kGaitParameterNames.begin(), kGaitParameterNames.end());
  n.resize(size());
  const auto percent = [](double f) { return std::to_string(static_cast<int>(f * 100.0 + 0.5)); };
  for (int k = 0; k < ss_points; ++k) {
    if (k == ss_points / 2) continue;
    const std::string at = "_ss" + percent(ssFraction(k));
    const int i = ssPointIndex(k);
    n[i] = "delta1" + at;
    n[i + 1] = "theta3" + at;
    n[i + 2] = "delta3" + at;
    n[i + 3] = "delta4" + at;
  }
  for (int k = 0; k < ds_points; ++k) {
    const std::string at = "_ds" + percent(dsFraction(k));
    n[dsPointIndex(k)] = "delta1" + at;
    n[dsPointIndex(k) + 1] = "theta3" + at;
  }
  if (landsWithImpact()) {
    n[impactSlopeIndex()] = "delta3s_fSS";
    n[impactSlopeIndex() + 1] = "delta4s_fSS";
  }
  return n;
}

GaitParameters extendPerParameter(const GaitParameters& thesis17, const Parameterisation& par,
                                  const std::array<double, 2>& ss_joints,
                                  const std::array<double, 2>& ds) {
  GaitParameters out(par.size());
  out.head(kNumGaitParameters) = thesis17.head(kNumGaitParameters);
  for (int k = 0; k < par.ss_points; ++k) {
    if (par.isFootPoint(k)) continue;
    out.segment(par.ssPointIndex(k), 4) << thesis17(kDelta1Int), thesis17(kTheta3Int),
        ss_joints[0], ss_joints[1];
  }
  for (int k = 0; k < par.ds_points; ++k) {
    out(par.dsPointIndex(k)) = ds[0];
    out(par.dsPointIndex(k) + 1) = ds[1];
  }
  if (par.landsWithImpact())
    out.segment(par.impactSlopeIndex(), 2).setConstant(thesis17(kDelta1sFSS));
  return out;
}

bool Parameterisation::isUsed(int i) const {
  if (landing != Landing::ImpactSingleSupport) return true;
  switch (i) {
    case kAlphaFDS: case kDelta1FDS: case kTheta3FDS: case kTDS:
    case kAlphadotISS: case kDelta1sISS: case kDelta2sISS:
      return false;
    default: return true;
  }
}

std::string Parameterisation::label() const {
  std::string s = "miossec";
  if (ss_points != 1 || ds_points != 0)
    s += "+ss" + std::to_string(ss_points) + "+ds" + std::to_string(ds_points);
  if (landing == Landing::ImpactSingleSupport) s += "+impact_ss";
  if (landing == Landing::ImpactDoubleSupport) s += "+impact_ds";
  if (basis == PathBasis::BSpline) s += "+bspline";
  return s;
}

}  // namespace gaitopt
