#include "impact_input.hpp"

#include <cmath>
#include <iostream>
#include <optional>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/tab_text.hpp"
#include "gaitopt/model/foot_on_ground.hpp"

namespace gaitopt::cli {
namespace {

bool parseDouble(const std::string& s, double& v) {
  const std::optional<double> x = parseDecimal(trimBlanks(s));
  if (x) v = *x;
  return x.has_value();
}

}  // namespace

std::vector<double> parseNumberList(const std::string& option, const std::string& text,
                                    std::size_t count) {
  const std::vector<std::string> parts = splitFields(text, ',');
  std::vector<double> out(parts.size());
  bool ok = parts.size() == count;
  for (std::size_t i = 0; ok && i < parts.size(); ++i) ok = parseDouble(parts[i], out[i]);
  if (!ok)
    throw BadImpactInput(option + ": expected " + std::to_string(count) +
                         " comma-separated finite numbers, got '" + printable(text) + "'");
  return out;
}

SampleRange parseSampleRange(const std::string& option, const std::string& text) {
  const std::vector<std::string> parts = splitFields(text, ':');
  SampleRange r{0.0, 0.0, 0};
  double n = 0.0;
  const bool ok = parts.size() == 3 && parseDouble(parts[0], r.a) && parseDouble(parts[1], r.b) &&
                  parseDouble(parts[2], n) && n >= 1.0 && n <= 10000.0 && n == std::floor(n);
  if (!ok)
    throw BadImpactInput(option + ": expected a:b:n (finite a, b; integer 1 <= n <= 10000), got '" +
                         printable(text) + "'");
  r.n = static_cast<int>(n);
  return r;
}

Vec5 foot2OnGround(const Model& model, const Vec5& q, const char* command) {
  const GroundProjection p = projectFoot2OnGround(model, q);
  if (std::abs(p.height) > kFoot2HeightTolerance || !p.converged)
    throw BadImpactInput("--q: foot 2 height z2 = " + shortNumber(p.height, "%.9g") +
                         " m; an impact needs foot 2 on the ground (|z2| <= 1e-5 m, then "
                         "projected onto it)");
  if (std::abs(p.height) > kGroundProjectionTolerance)
    std::cerr << "gaitopt " << command << ": foot 2 was " << shortNumber(p.height, "%.3g")
              << " m off the ground: --q projected onto it (largest change "
              << shortNumber(p.max_change, "%.3g") << " rad; the configuration used is q in the "
              << "output)\n";
  return p.q;
}

ImpactModelKind parseImpactModel(const std::string& text) {
  return text == "differential" ? ImpactModelKind::Differential : ImpactModelKind::Algebraic;
}

void requireFriction(const std::string& option, double mu) {
  if (!std::isfinite(mu) || mu < 0.0)
    throw BadImpactInput(option + ": friction coefficient must be finite and >= 0, got " +
                         shortNumber(mu));
}

int exitCodeOf(const char* command, const std::function<int()>& run) {
  try {
    return run();
  } catch (const BadImpactInput& e) {
    std::cerr << "gaitopt " << command << ": error: " << e.what() << "\n";
    return kExitBadInput;
  }
}

}  // namespace gaitopt::cli
