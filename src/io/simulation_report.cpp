#include "gaitopt/io/simulation_report.hpp"

#include <cmath>
#include <sstream>

#include "gaitopt/gait/constraints/contact.hpp"
#include "gaitopt/io/json_writer.hpp"
#include "gaitopt/sim/cycle_convergence.hpp"

namespace gaitopt {

std::string simulationSummaryJson(const WalkResult& r, const SimulationRun& run) {
  const WalkRequest& req = run.request;
  JsonWriter w;
  w.beginObject();
  w.key("outcome").value(outcomeName(r.outcome));
  w.key("message").value(r.message);
  w.key("converged_to_cycle").value(convergedToCycle(r, run.cycle_alphad_start));
  w.key("tracks_reference").value(tracksReference(r, run.cycle_alphad_start));
  w.key("steps_requested").value(req.steps);
  w.key("steps_completed")
      .value(static_cast<int>(r.steps.size()) - (r.outcome == WalkOutcome::Completed ? 0 : 1));
  w.key("gait").value(run.gait);
  w.key("plant").value(run.plant.empty() ? std::string("gait robot") : run.plant);
  w.key("bandwidth").value(req.bandwidth);
  w.key("perturbation").beginObject();
  w.key("alphad").value(req.dalphad0);
  w.key("dq").value(req.dq0);
  w.key("slope").value(req.ground_slope);
  w.endObject();
  w.key("impact_model").value(run.impact_model);
  w.key("ds_control").value(toString(req.ds_control));
  w.key("torque_limits").value(req.torque_limits);
  w.key("ground_friction_coefficient").value(req.plant_friction_coefficient);
  int saturated = 0;
  for (const WalkStep& s : r.steps) saturated += s.saturated_samples;
  w.key("saturated_samples").value(saturated);
  w.key("cycle_alphad_start").value(run.cycle_alphad_start);
  w.key("last_alphad_start").value(r.steps.empty() ? 0.0 : r.steps.back().alphad_start);
  w.endObject();
  return w.str() + "\n";
}

std::string walkStepsCsv(const WalkResult& r) {
  std::ostringstream o;
  o << "step,t_start,t_touchdown,t_liftoff,alphad_start,max_output_error,"
       "touchdown_event_residual,touchdown_foot_speed,energy_start,energy_touchdown,motor_work,"
       "friction_loss,min_normal_force,impact_behaviour,impact_energy_loss,impulse1_x,impulse1_z,"
       "impulse2_x,impulse2_z,energy_end,step_motor_work,step_friction_loss,energy_balance_error,"
       "saturated_samples,first_saturation_time\n";
  for (const WalkStep& s : r.steps)
    o << s.step << ',' << formatDouble(s.t_start) << ',' << formatDouble(s.t_touchdown) << ','
      << formatDouble(s.t_liftoff) << ',' << formatDouble(s.alphad_start) << ','
      << formatDouble(s.max_output_error) << ',' << formatDouble(s.touchdown_event_residual)
      << ',' << formatDouble(s.touchdown_foot_speed) << ',' << formatDouble(s.energy_start)
      << ',' << formatDouble(s.energy_touchdown) << ',' << formatDouble(s.motor_work) << ','
      << formatDouble(s.friction_loss) << ',' << formatDouble(s.min_normal_force) << ','
      << s.impact_behaviour << ',' << formatDouble(s.impact_energy_loss) << ','
      << formatDouble(s.impulse1(0)) << ',' << formatDouble(s.impulse1(1)) << ','
      << formatDouble(s.impulse2(0)) << ',' << formatDouble(s.impulse2(1)) << ','
      << formatDouble(s.energy_end) << ',' << formatDouble(s.step_motor_work) << ','
      << formatDouble(s.step_friction_loss) << ',' << formatDouble(stepEnergyBalanceError(s))
      << ',' << s.saturated_samples << ',' << formatDouble(s.first_saturation_time) << '\n';
  return o.str();
}

std::string walkTrackingCsv(const WalkResult& r, double mu) {
  std::ostringstream o;
  o << "t,step,phase,error1,error2,error3,error4,R1z,R2z,cone_margin1,cone_margin2\n";
  for (const WalkSample& s : r.samples) {
    o << formatDouble(s.t) << ',' << s.step << ',' << (s.single_support ? "SS" : "DS");
    for (int j = 0; j < 4; ++j) o << ',' << formatDouble(s.output_error(j));
    // The cone margins μ R_z − |R_x| (3.48); the swing foot's is 0.
    o << ',' << formatDouble(s.R1(1)) << ',' << formatDouble(s.R2(1)) << ','
      << formatDouble(-frictionConeExcess(s.R1, mu)) << ','
      << formatDouble(s.single_support ? 0.0 : -frictionConeExcess(s.R2, mu)) << '\n';
  }
  return o.str();
}

}  // namespace gaitopt
