#include "gaitopt/ident/opensim_conventions.hpp"

#include <algorithm>
#include <cmath>

#include "gaitopt/ident/data_error.hpp"

namespace gaitopt {

namespace {

constexpr double kPi = 3.14159265358979323846;
// A walking knee bends by ~60°; its angle stays within this of zero on the extension side.
constexpr double kKneeSide = 0.35;  // [rad], 20°
constexpr double kContactForce = 20.0;  // [N] for the CoP side check

const char* const kCoordinates[] = {"pelvis_tilt",   "pelvis_tx",     "pelvis_ty",
                                    "hip_flexion_r", "hip_flexion_l", "knee_angle_r",
                                    "knee_angle_l",  "lumbar_extension"};

// Marker sets of common protocols, first match used: pelvis, shoulders, heels (right, left).
const std::vector<std::vector<std::string>> kPelvisSets{
    {"R.ASIS", "L.ASIS", "V.Sacral"}, {"R.ASIS", "L.ASIS", "S2"},
    {"R.ASIS", "L.ASIS", "R.PSIS", "L.PSIS"}, {"RASI", "LASI", "SACR"},
    {"RASI", "LASI", "RPSI", "LPSI"}};
const std::vector<std::vector<std::string>> kShoulderSets{
    {"R.Acromium", "L.Acromium"}, {"R.Acromion", "L.Acromion"}, {"R.Shoulder", "L.Shoulder"},
    {"RSHO", "LSHO"}};
const std::vector<std::vector<std::string>> kHeelSets{{"R.Heel", "L.Heel"}, {"RHEE", "LHEE"},
                                                     {"R.Calc", "L.Calc"}};

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// Prefixes P with columns P+vx, P+vy, P+px, P+py.
std::vector<std::string> platePrefixes(const OpenSimTable& grf) {
  std::vector<std::string> out;
  for (const std::string& c : grf.columns) {
    if (c.size() < 2 || c.compare(c.size() - 2, 2, "vx") != 0) continue;
    const std::string p = c.substr(0, c.size() - 2);
    if (grf.hasColumn(p + "vy") && grf.hasColumn(p + "px") && grf.hasColumn(p + "py"))
      out.push_back(p);
  }
  return out;
}

// +1 when the prefix names the right side (a token r/R/right), −1 the left, 0 neither.
int sideInName(const std::string& prefix) {
  int side = 0;
  std::size_t start = 0;
  while (start <= prefix.size()) {
    const std::size_t end = std::min(prefix.find_first_of("_.", start), prefix.size());
    std::string token = prefix.substr(start, end - start);
    std::transform(token.begin(), token.end(), token.begin(), [](unsigned char ch) { return std::tolower(ch); });
    if (token == "r" || token == "right") side = 1;
    if (token == "l" || token == "left") side = -1;
    start = end + 1;
  }
  return side;
}

// Mean CoP z of a plate while it carries the foot; NaN when it never does or has no pz.
double meanLoadedCopZ(const OpenSimTable& grf, const std::string& prefix) {
  if (!grf.hasColumn(prefix + "pz")) return std::nan("");
  const Eigen::VectorXd fy = grf.column(prefix + "vy"), pz = grf.column(prefix + "pz");
  double sum = 0.0;
  int n = 0;
  for (Eigen::Index k = 0; k < fy.size(); ++k)
    if (fy(k) > kContactForce) sum += pz(k), ++n;
  return n ? sum / n : std::nan("");
}

void resolvePlates(const OpenSimTable& grf, const ConventionHints& h, OpenSimConventions& c) {
  for (const auto* given : {&h.right_plate, &h.left_plate})
    if (*given && !grf.hasColumn(**given + "vy"))
      throw DataError(grf.file, **given + "vy", 0,
                      "the conventions name plate prefix '" + **given + "', the file has no such columns");
  const std::vector<std::string> found = platePrefixes(grf);
  std::string how = "as given";
  if (h.right_plate && h.left_plate) {
    c.right_plate = *h.right_plate, c.left_plate = *h.left_plate;
  } else if (found.size() == 2 && sideInName(found[0]) * sideInName(found[1]) == -1) {
    const bool first_right = sideInName(found[0]) == 1;
    c.right_plate = found[first_right ? 0 : 1], c.left_plate = found[first_right ? 1 : 0];
    how = "detected from the column names";
  } else if (found.size() == 2) {
    const double z0 = meanLoadedCopZ(grf, found[0]), z1 = meanLoadedCopZ(grf, found[1]);
    if (!(std::isfinite(z0) && std::isfinite(z1)))
      throw DataError(grf.file, "", 0,
                      "plates '" + found[0] + "' and '" + found[1] +
                          "' do not name their foot and cannot be told apart by their centres of "
                          "pressure: give plates: {right: ..., left: ...} in --conventions");
    c.right_plate = found[z0 > z1 ? 0 : 1], c.left_plate = found[z0 > z1 ? 1 : 0];
    how = "detected from the centres of pressure (OpenSim Z points to the subject's right)";
  } else {
    throw DataError(grf.file, "", 0,
                    std::to_string(found.size()) + " force-plate column sets (" + joined(found) +
                        ") where one per foot is needed: give plates: {right: PREFIX, left: PREFIX} "
                        "in --conventions");
  }
  const double zr = meanLoadedCopZ(grf, c.right_plate), zl = meanLoadedCopZ(grf, c.left_plate);
  if (std::isfinite(zr) && std::isfinite(zl) && zr < zl)
    throw DataError(grf.file, c.right_plate + "pz", 0,
                    "the right-foot plate's centre of pressure lies left of the left-foot plate's "
                    "(mean z " + std::to_string(zr) + " < " + std::to_string(zl) +
                        " m; OpenSim Z points right): the plates are swapped");
  c.statements.push_back("force plates: right '" + c.right_plate + "', left '" + c.left_plate +
                         "' (" + how + ")");
}

void resolveCoordinates(const OpenSimTable& ik, const ConventionHints& h, OpenSimConventions& c) {
  for (const char* name : kCoordinates) {
    const auto it = h.coordinates.find(name);
    c.coordinates[name] = it == h.coordinates.end() ? name : it->second;
    if (!ik.hasColumn(c.coordinates[name]))
      throw DataError(ik.file, c.coordinates[name], 0,
                      "IK column missing (or ambiguous): map " + std::string(name) +
                          " to the file's column in --conventions 'coordinates'");
  }
  if (!h.coordinates.empty())
    c.statements.push_back("IK coordinates renamed by the conventions file");
}

// The sign read off the knee angles: one side of zero holds the walking range.
std::optional<KneeFlexion> kneeFromData(const OpenSimTable& ik, const OpenSimConventions& c,
                                        std::string& range) {
  const double unit = ik.in_degrees ? kPi / 180.0 : 1.0;
  double lo = 1e300, hi = -1e300;
  for (const char* knee : {"knee_angle_r", "knee_angle_l"}) {
    const Eigen::VectorXd a = unit * ik.column(c.column(knee));
    lo = std::min(lo, a.minCoeff()), hi = std::max(hi, a.maxCoeff());
  }
  range = std::to_string(int(std::lround(lo * 180.0 / kPi))) + ".." +
          std::to_string(int(std::lround(hi * 180.0 / kPi))) + " deg";
  if (lo > -kKneeSide && hi > kKneeSide) return KneeFlexion::Positive;
  if (hi < kKneeSide && lo < -kKneeSide) return KneeFlexion::Negative;
  return std::nullopt;
}

const char* signName(KneeFlexion k) { return k == KneeFlexion::Positive ? "positive" : "negative"; }

void resolveKnee(const OpenSimTable& ik, const ConventionHints& h, OpenSimConventions& c) {
  std::string range;
  const std::optional<KneeFlexion> data = kneeFromData(ik, c, range);
  if (h.knee && data && *h.knee != *data)
    throw DataError(ik.file, c.column("knee_angle_r"), 0,
                    std::string("the ") + h.knee_source + " says knee flexion is " + signName(*h.knee) +
                        ", the knee angles (" + range + ") say " + signName(*data));
  if (!h.knee && !data)
    throw DataError(ik.file, c.column("knee_angle_r"), 0,
                    "knee angles " + range + " do not tell the sign of flexion: give knee_flexion: "
                    "positive|negative in --conventions, or the model with --model");
  c.knee = h.knee ? *h.knee : *data;
  c.statements.push_back(std::string("knee flexion: knee_angle ") + signName(c.knee) + " (" +
                         (h.knee ? h.knee_source + ", " : std::string()) + "knee angles " + range +
                         (data ? "" : ", undecided by the data") + ")");
}

std::vector<std::string> markerSet(const TrcData& trc, const std::optional<std::vector<std::string>>& given,
                                   const std::vector<std::vector<std::string>>& sets,
                                   const char* what, std::vector<std::string>& statements) {
  const auto present = [&](const std::vector<std::string>& s) {
    return std::all_of(s.begin(), s.end(), [&](const std::string& m) {
      return std::find(trc.markers.begin(), trc.markers.end(), m) != trc.markers.end();
    });
  };
  if (given) {
    for (const std::string& m : *given) trc.marker(m);  // names the missing one
    statements.push_back(std::string(what) + " markers: " + joined(*given) + " (as given)");
    return *given;
  }
  for (const auto& s : sets) {
    if (!present(s)) continue;
    statements.push_back(std::string(what) + " markers: " + joined(s) + " (detected)");
    return s;
  }
  std::string known;
  for (const auto& s : sets) known += (known.empty() ? "" : "; ") + joined(s);
  throw DataError(trc.file, what, 0,
                  std::string("no known ") + what + " marker set (" + known +
                      "): name them under markers in --conventions");
}

}  // namespace

OpenSimConventions resolveConventions(const OpenSimTable& ik, const OpenSimTable& grf,
                                      const TrcData* trc, const ConventionHints& hints) {
  OpenSimConventions c;
  if (!hints.model.empty()) c.statements.push_back("model: " + hints.model + " (model file)");
  resolvePlates(grf, hints, c);
  resolveCoordinates(ik, hints, c);
  resolveKnee(ik, hints, c);
  if (trc) {
    c.pelvis_markers = markerSet(*trc, hints.pelvis_markers, kPelvisSets, "pelvis", c.statements);
    c.shoulder_markers =
        markerSet(*trc, hints.shoulder_markers, kShoulderSets, "shoulder", c.statements);
    c.heel_markers = markerSet(*trc, hints.heel_markers, kHeelSets, "heel", c.statements);
    if (c.heel_markers.size() != 2)
      throw DataError(trc->file, "heel", 0, "heel markers: give exactly two (right, left)");
  }
  return c;
}

}  // namespace gaitopt
