#pragma once
// Controller export: N consecutive steps of a gait at a fixed rate, with the physical stance
// leg alternating, in the quantities a joint-level controller consumes (seed 002 §3): phase
// variable α and its rates, joint-side motor angles φ = D_Γᵀ q per physical motor, feedforward
// torques Γ* split into their dynamic parts, planned feet and reactions in the world frame.
// Also the virtual-constraint polynomials of each phase with a normalised phase variable.
#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "gaitopt/control/gait_ramp.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/io/json_writer.hpp"

namespace gaitopt {

enum class Leg { Left, Right };

// Physical motors in export order; arrays indexed by this order.
inline const std::array<const char*, 4> kPhysicalJoints{"knee_left", "hip_left", "hip_right",
                                                        "knee_right"};

// Rows at the exact phase boundaries, in addition to the fixed-rate samples: the ending
// phase's last row (s = 1) then the starting phase's first row (s = 0), both at the boundary
// time and flagged with the event.
enum class ExportEvent { None = 0, Touchdown = 1, LiftOff = 2 };

struct ExportRow {
  double t = 0.0;   // from the start of the first step [s]
  int step = 0;     // 0-based; step k = SS_k followed by DS_k
  Phase phase = Phase::SingleSupport;
  Leg stance = Leg::Left;  // the physical leg carried as leg 1 (in DS: the front leg)
  ExportEvent event = ExportEvent::None;
  // Normalised phase s = (α − α_start)/(α_end − α_start) of the row's phase and its rates.
  double s = 0.0, sd = 0.0, sdd = 0.0;
  double alpha = 0.0, alphad = 0.0, alphadd = 0.0;  // leg-1 tibia from the vertical
  Vec2 hip = Vec2::Zero();                          // world frame, first stance foot at 0
  double trunk_angle = 0.0;  // θ3 − π/2: trunk from the vertical, > 0 leaning backward
  // Per physical joint (kPhysicalJoints order).
  Vec4 phi = Vec4::Zero(), phid = Vec4::Zero(), phidd = Vec4::Zero(), motor = Vec4::Zero();
  Vec4 tau = Vec4::Zero();  // Γ* = inertial + gravity + contact + friction
  Vec4 tau_inertial = Vec4::Zero(), tau_gravity = Vec4::Zero(), tau_contact = Vec4::Zero(),
       tau_friction = Vec4::Zero();
  // Γ* = B s̈ + C ṡ² + G + K + F with G = tau_gravity, K = tau_contact (DS, planned reactions),
  // F = tau_friction: the coefficients B of s̈ and C of ṡ² [N·m].
  Vec4 tau_B = Vec4::Zero(), tau_C = Vec4::Zero();
  Vec2 foot_left = Vec2::Zero(), foot_right = Vec2::Zero();
  Vec2 R_left = Vec2::Zero(), R_right = Vec2::Zero();
};

struct ExportRequest {
  int steps = 1;        // ≥ 1
  double rate = 1000;   // Hz, > 0
  Leg first_stance = Leg::Left;
  RotorModel rotor = RotorModel::Exact;  // of the feedforward's model (metadata)
  int ramp_steps = 0;  // > 0: a ramp of this many steps in and out around `steps` (gait_ramp.hpp)
  std::vector<double> ramp_rates;  // then the SS start rates of its steps (metadata)
};

// The multi-step trajectory. `model` carries the robot file's full friction (the feedforward
// must overcome it whatever the gait was optimised with) and the feedforward's rotor model;
// `evaluation.motion_computed` required. Samples t_i = i/rate for 0 ≤ t_i ≤ steps·(T_SS +
// T_DS); a sample on a phase boundary belongs to the phase that starts there (the last one to
// the final DS); plus the event rows (ExportEvent) at every boundary between phases.
std::vector<ExportRow> exportTrajectory(const GaitEvaluator& evaluator,
                                        const GaitEvaluation<double>& evaluation,
                                        const Model& model, const ExportRequest& request);

// The samples of a multi-step walk (gait_ramp.hpp) as exported rows with the event rows of
// its phase boundaries inserted; leg 1 of the first SS is the physical leg `first_stance`.
std::vector<ExportRow> exportWalk(const GaitEvaluator& evaluator, const Model& model,
                                  const std::vector<WalkStepMotion>& walk,
                                  const std::vector<PlannedSample>& samples, Leg first_stance);

// One exported sample from a trajectory row of one step (frame of foot 1) placed in the world;
// its phase terms (s and the feedforward's B, C) are left zero for setPhaseTerms.
ExportRow exportRow(const Model& model, const TrajectoryRow& row, int step, Leg stance,
                    double foot1_x, double t);

// α at the start and at the end of `phase` of `motion`: the range of s.
std::pair<double, double> phaseAlphaRange(const GaitMotion<double>& motion, Phase phase);

// The feedforward of `phase` at the path point α, per unit normalised phase, in leg-1 order
// (knee 1, hip 1, hip 2, knee 2): Γ = B s̈ + C ṡ² + G + (DS) K + F(ω), ω = dφ/ds ṡ.
struct FeedforwardTerms {
  Vec4 B, C, G;  // [N·m]
  Vec4 dphi_ds;  // joint-side motor angle rates per unit ṡ [rad]
  Vec4 phi;      // joint-side motor angles there [rad]
};
FeedforwardTerms feedforwardTerms(const Model& model, const GaitMotion<double>& motion,
                                  Phase phase, double alpha);

// s, ṡ, s̈ of `row` in its phase of `motion`, and B, C there.
void setPhaseTerms(ExportRow& row, const Model& model, const GaitMotion<double>& motion);

// `#` metadata lines of the export: key → value, written in key order.
using ExportMetadata = std::map<std::string, std::string>;

ExportMetadata exportMetadata(const GaitFile& gait, const GaitEvaluation<double>& evaluation,
                              const ExportRequest& request);

// Parts of the JSON export, shared with the gait library (export/gait_library.hpp).
// A file embedded verbatim under `key`: its path, SHA-256 and text (`yaml`).
void writeEmbeddedFile(JsonWriter& w, const std::string& key, const std::string& path);
// The same for a document made in memory, `file` saying what it stands for.
void writeEmbeddedText(JsonWriter& w, const std::string& key, const std::string& file,
                       const std::string& text);
// `cyclic_gait`: speed, step length, T_SS, T_DS of one evaluated gait.
void writeCyclicGait(JsonWriter& w, const GaitEvaluation<double>& evaluation);
// `feedforward`: the rotor model of `model`, the decomposition, the friction coefficients.
void writeFeedforwardHead(JsonWriter& w, const Model& model);
// `conventions`: frame, α, s, joint orders, φ, polynomials, tables, events.
void writeExportConventions(JsonWriter& w);
// `phases`: per phase the α range, virtual constraints in s and the feedforward tables of
// `model` (polynomial paths only).
void writeExportPhases(JsonWriter& w, const Model& model, const GaitMotion<double>& motion);

// Column names and units in file order.
std::vector<std::pair<std::string, std::string>> exportColumns();

std::string exportCsv(const ExportMetadata& meta, const std::vector<ExportRow>& rows);

// JSON (schema kControllerExportSchema, docs/commands/export.md): the gait and robot files
// embedded verbatim (io/controller_export_file.hpp reads them back), the cyclic gait, the
// feedforward's rotor model (`model`'s), metadata, columns with units, per phase the virtual
// constraints as polynomials of a normalised phase variable, and the samples column-wise.
std::string exportJson(const GaitFile& gait, const Model& model,
                       const GaitEvaluation<double>& evaluation, const ExportMetadata& meta,
                       const std::vector<ExportRow>& rows);

struct ExportCsvFile {
  ExportMetadata meta;
  std::vector<ExportRow> rows;
};

// Reads a file written by exportCsv; throws ConfigError naming the file, row and column.
ExportCsvFile readExportCsv(const std::string& path);

// Coefficients a_k of p(s) = Σ a_k s^k for p(x) = Σ c_k (x − x0)^k and s = (x − x0)/h.
std::vector<double> normalisedMonomials(const LocalPolynomial<double>& p, double h);

// Bernstein (Bézier) coefficients on s ∈ [0, 1] of the monomial coefficients a_k.
std::vector<double> bezierFromMonomials(const std::vector<double>& a);

}  // namespace gaitopt
