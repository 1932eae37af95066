#include "gaitopt/gait_parameters.hpp"

namespace gaitopt {

const std::array<const char*, kNumGaitParameters> kGaitParameterNames = {
    "alpha_iDS",   "delta1_iDS",   "theta3_iDS",   "d",           "alpha_fDS",   "delta1_fDS",
    "theta3_fDS",  "delta1_int",   "theta3_int",   "x2r_int",     "z2_int",      "alphadot_iSS",
    "delta1s_iSS", "delta2s_iSS",  "delta1s_fSS",  "delta2s_fSS", "T_DS"};

}  // namespace gaitopt
