#include "gaitopt/impact/algebraic_impact_equations.hpp"

namespace gaitopt {

std::vector<ImpactBehaviour> allImpactBehaviours() {
  std::vector<ImpactBehaviour> out;
  for (Foot1Behaviour f1 : {Foot1Behaviour::Lift, Foot1Behaviour::Stick, Foot1Behaviour::SlipPlus,
                            Foot1Behaviour::SlipMinus})
    for (Foot2Behaviour f2 :
         {Foot2Behaviour::Stick, Foot2Behaviour::SlipPlus, Foot2Behaviour::SlipMinus})
      out.push_back({f1, f2});
  return out;
}

const char* toString(Foot1Behaviour b) {
  switch (b) {
    case Foot1Behaviour::Lift: return "lift";
    case Foot1Behaviour::Stick: return "stick";
    case Foot1Behaviour::SlipPlus: return "slip+";
    case Foot1Behaviour::SlipMinus: return "slip-";
  }
  return "?";
}

const char* toString(Foot2Behaviour b) {
  switch (b) {
    case Foot2Behaviour::Stick: return "stick";
    case Foot2Behaviour::SlipPlus: return "slip+";
    case Foot2Behaviour::SlipMinus: return "slip-";
  }
  return "?";
}

std::vector<SlackInfo> impactSlacks(ImpactBehaviour b) {
  std::vector<SlackInfo> out;
  const auto stick = [&out](const char* cone_minus, const char* cone_plus, const char* normal) {
    out.push_back({SlackKind::Impulse, cone_minus});
    out.push_back({SlackKind::Impulse, cone_plus});
    out.push_back({SlackKind::Impulse, normal});
  };
  const auto slip = [&out](const char* normal, const char* velocity) {
    out.push_back({SlackKind::Impulse, normal});
    out.push_back({SlackKind::Velocity, velocity});
  };
  switch (b.foot1) {
    case Foot1Behaviour::Lift: out.push_back({SlackKind::Velocity, "V1z+"}); break;
    case Foot1Behaviour::Stick: stick("mu*I1z - I1x", "mu*I1z + I1x", "I1z"); break;
    case Foot1Behaviour::SlipPlus: slip("I1z", "V1x+"); break;
    case Foot1Behaviour::SlipMinus: slip("I1z", "-V1x+"); break;
  }
  switch (b.foot2) {
    case Foot2Behaviour::Stick: stick("mu*I2z - I2x", "mu*I2z + I2x", "I2z"); break;
    case Foot2Behaviour::SlipPlus: slip("I2z", "V2x+"); break;
    case Foot2Behaviour::SlipMinus: slip("I2z", "-V2x+"); break;
  }
  return out;
}

}  // namespace gaitopt
