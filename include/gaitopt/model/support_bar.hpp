#pragma once
// The lateral support bar acts as a point mass at the hip (§1.4.2.4); folding it into the
// trunk parameters (1.24) leaves the model structure unchanged.
namespace gaitopt {

struct TrunkParameters {
  double mass;        // m3*
  double com_offset;  // s3*, from the hip
  double inertia;     // I_y3*, about the new CoM
};

TrunkParameters trunkWithBar(double m3, double s3, double I3, double equivalent_mass);

// (1.29) with l_G = L_b/2, the value the thesis uses (7.5 kg for its bar).
double barEquivalentMass(double bar_length, double overhang, double bar_mass,
                         double counterweight_mass);

}  // namespace gaitopt
