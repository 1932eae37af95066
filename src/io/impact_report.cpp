#include "gaitopt/io/impact_report.hpp"

namespace gaitopt {
namespace {

void writeBehaviour(JsonWriter& w, ImpactBehaviour b) {
  w.key("foot1").value(toString(b.foot1));
  w.key("foot2").value(toString(b.foot2));
}

}  // namespace

void writeImpactResultFields(JsonWriter& w, const ImpactResult& r) {
  w.key("model").value(toString(r.model));
  w.key("mu").value(r.mu);
  w.key("V2_minus").value(r.V2_minus);
  w.key("status").value(toString(r.status));
  w.key("solutions").beginArray();
  for (const ImpactSolution& s : r.solutions) {
    w.beginObject();
    w.key("behaviour").beginObject();
    writeBehaviour(w, s.behaviour);
    w.endObject();
    w.key("boundary").value(s.boundary);
    w.key("Xd_plus").value(s.Xd_plus);
    w.key("impulse_foot1").value(s.impulse1);
    w.key("impulse_foot2").value(s.impulse2);
    w.key("energy_loss").value(s.energy_loss);
    w.key("contact").beginObject();  // post-impact contact state from the final velocities
    writeBehaviour(w, s.contact);
    w.endObject();
    w.key("V_plus").value(s.V_plus);
    w.key("accumulation").value(s.accumulation);
    if (s.accumulation) w.key("accumulation_cycle_length").value(s.accumulation_cycle_length);
    w.key("phases").beginArray();
    for (const ImpactPhase& p : s.phases) {
      w.beginObject();
      writeBehaviour(w, p.behaviour);
      w.key("tau_end").value(p.tau_end);
      w.endObject();
    }
    w.endArray();
    w.endObject();
  }
  w.endArray();
  w.key("notes").beginArray();
  for (const std::string& n : r.notes) w.value(n);
  w.endArray();
}

}  // namespace gaitopt
