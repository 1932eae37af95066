#include "gaitopt/io/simulation_report.hpp"

#include <cmath>
#include <sstream>

#include "gaitopt/gait/constraints/contact.hpp"
#include "gaitopt/io/csv_table.hpp"
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
  w.key("gain_scale").value(req.gain_scale);
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

namespace {

CsvRow walkStepRow(const WalkStep& s) {
  CsvRow row;
  row.integer(s.step).number(s.t_start).number(s.t_touchdown).number(s.t_liftoff);
  row.number(s.alphad_start).number(s.max_output_error).number(s.touchdown_event_residual);
  row.number(s.touchdown_foot_speed).number(s.energy_start).number(s.energy_touchdown);
  row.number(s.motor_work).number(s.friction_loss).number(s.min_normal_force);
  row.text(s.impact_behaviour).number(s.impact_energy_loss).numbers(s.impulse1).numbers(s.impulse2);
  row.number(s.energy_end).number(s.step_motor_work).number(s.step_friction_loss);
  row.number(stepEnergyBalanceError(s)).integer(s.saturated_samples);
  return row.number(s.first_saturation_time);
}

}  // namespace

std::string walkStepsCsv(const WalkResult& r) {
  std::ostringstream o;
  o << csvHeader({"step", "t_start", "t_touchdown", "t_liftoff", "alphad_start", "max_output_error",
                  "touchdown_event_residual", "touchdown_foot_speed", "energy_start",
                  "energy_touchdown", "motor_work", "friction_loss", "min_normal_force",
                  "impact_behaviour", "impact_energy_loss", "impulse1_x", "impulse1_z",
                  "impulse2_x", "impulse2_z", "energy_end", "step_motor_work", "step_friction_loss",
                  "energy_balance_error", "saturated_samples", "first_saturation_time"});
  for (const WalkStep& s : r.steps) o << walkStepRow(s).line();
  return o.str();
}

std::string walkTrackingCsv(const WalkResult& r, double mu) {
  std::ostringstream o;
  o << csvHeader({"t", "step", "phase", "error1", "error2", "error3", "error4", "R1z", "R2z",
                  "cone_margin1", "cone_margin2"});
  for (const WalkSample& s : r.samples) {
    CsvRow row;
    row.number(s.t).integer(s.step).text(s.single_support ? "SS" : "DS").numbers(s.output_error);
    // The cone margins μ R_z − |R_x| (3.48); the swing foot's is 0.
    row.number(s.R1(1)).number(s.R2(1)).number(-frictionConeExcess(s.R1, mu));
    o << row.number(s.single_support ? 0.0 : -frictionConeExcess(s.R2, mu)).line();
  }
  return o.str();
}

}  // namespace gaitopt
