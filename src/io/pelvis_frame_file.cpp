#include "gaitopt/io/pelvis_frame_file.hpp"

#include <cmath>

namespace gaitopt {

namespace {

std::array<double, 2> point(const YamlMap& m, const std::string& key) {
  const std::vector<double> v = m.numbers(key, 2);
  return {v[0], v[1]};
}

}  // namespace

std::optional<PelvisFrame> readPelvisFrame(const YamlMap& doc, double trunk_mass) {
  const std::optional<YamlMap> m = doc.optionalMap("pelvis_frame");
  if (!m) return std::nullopt;
  PelvisFrame f;
  f.hip = point(*m, "hip");
  f.pelvis_com = point(*m, "pelvis_com");
  f.back = point(*m, "back");
  f.torso_com = point(*m, "torso_com");
  f.pelvis_mass = m->number("pelvis_mass");
  f.torso_mass = m->number("torso_mass");
  if (!(f.pelvis_mass > 0.0 && f.torso_mass > 0.0))
    throw m->error("pelvis_mass", "pelvis_mass and torso_mass must be > 0");
  if (std::abs(f.pelvis_mass + f.torso_mass - trunk_mass) > 0.01 * trunk_mass)
    throw m->error("torso_mass", "pelvis_mass + torso_mass = " +
                                     showNumber(f.pelvis_mass + f.torso_mass) +
                                     " kg must be the trunk mass m3 = " + showNumber(trunk_mass) + " kg");
  return f;
}

std::optional<PelvisFrame> loadPelvisFrame(const std::string& path) {
  const YamlMap doc(loadYamlFile(path), path, "");
  return readPelvisFrame(doc, doc.map("masses").number("m3"));
}

}  // namespace gaitopt
