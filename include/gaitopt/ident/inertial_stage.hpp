#pragma once
// The last-resort `inertial` stage of the diagnosis (ident/diagnose.hpp): the base inertial
// parameters (ident/inertial_fit.hpp) fitted on top of the selected effects by physically
// consistent weighted least squares and tested like a named candidate with r = rank degrees of
// freedom; once accepted, a backward step drops the selected effects it makes insignificant and
// refits the rest.
#include "gaitopt/ident/model_selection.hpp"

namespace gaitopt::diagnosis {

// On top of the selection `sel` (whose causes `dg` holds): sets dg.inertial and, when the
// stage is accepted, the remaining causes, the `inertial` cause and dg.extended_robot.
void addInertialStage(const Context& ctx, const Linearisation& lin, const Selection& sel,
                      const DiagnoseOptions& o, Diagnosis& dg);

}  // namespace gaitopt::diagnosis
