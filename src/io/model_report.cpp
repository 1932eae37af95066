#include "gaitopt/io/model_report.hpp"

#include "gaitopt/model/dynamics_floating.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/inverse_dynamics.hpp"
#include "gaitopt/io/json_writer.hpp"

namespace gaitopt {
namespace {

void writePinned(JsonWriter& w, const Model& model, const Vec5& q, const Vec5& qd) {
  const PinnedTerms<double> t = pinnedTerms(model, q, qd);
  w.key("pinned").beginObject();
  w.key("A").value(t.A);
  w.key("C").value(t.C);
  w.key("G").value(t.G);
  w.key("D_Gamma").value(model.D_Gamma);
  w.key("foot2").value(t.foot2);
  w.key("D2").value(t.D2);
  w.key("H2").value(t.H2);
  w.key("com").value(t.com);
  w.key("total_mass").value(model.total_mass);
  w.key("angular_momentum_foot1").value(angularMomentumFoot1(t, qd));
  w.endObject();
}

void writeFloating(JsonWriter& w, const Model& model, const Vec5& q, const Vec5& qd) {
  Vector7<double> X, Xd;
  floatingStateFromPinned(model, q, qd, X, Xd);
  const FloatingTerms<double> f = floatingTerms(model, X, Xd);
  w.key("floating").beginObject();
  w.key("X").value(f.X);
  w.key("Xd").value(f.Xd);
  w.key("A").value(f.A);
  w.key("C").value(f.C);
  w.key("G").value(f.G);
  w.key("D1").value(f.D1);
  w.key("D2").value(f.D2);
  w.key("H1").value(f.H1);
  w.key("H2").value(f.H2);
  w.endObject();
}

void writeInverseDynamics(JsonWriter& w, const Model& model, const Vec5& q, const Vec5& qd,
                          const Vec5& qdd) {
  // Reported with the exact sign of Coulomb friction (the smooth one is for optimisation).
  const auto r = inverseDynamicsSS(model, q, qd, qdd, SignMode::Exact);
  w.key("inverse_dynamics_ss").beginObject();
  w.key("gamma_star").value(r.gamma_star);
  w.key("gamma").value(r.gamma);
  w.key("alpha_row_residual").value(r.alpha_row_residual);
  w.key("R1").value(r.R1);
  w.endObject();
}

}  // namespace

std::string modelReportJson(const Model& model, const Vec5& q, const Vec5& qd,
                            const std::optional<Vec5>& qdd) {
  JsonWriter w;
  w.beginObject();
  w.key("robot").value(model.robot.name);
  w.key("q").value(q);
  w.key("qd").value(qd);
  writePinned(w, model, q, qd);
  writeFloating(w, model, q, qd);
  if (qdd) writeInverseDynamics(w, model, q, qd, *qdd);
  w.endObject();
  return w.str() + "\n";
}

}  // namespace gaitopt
