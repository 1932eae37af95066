#include "impact_input.hpp"

#include <cmath>
#include <iostream>
#include <sstream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"

namespace gaitopt::cli {
namespace {

bool parseDouble(const std::string& s, double& v) {
  try {
    std::size_t used = 0;
    v = std::stod(s, &used);
    return used == s.size() && std::isfinite(v);
  } catch (const std::exception&) {
    return false;
  }
}

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, sep)) parts.push_back(part);
  if (!text.empty() && text.back() == sep) parts.push_back("");
  return parts;
}

}  // namespace

std::vector<double> parseNumberList(const std::string& option, const std::string& text,
                                    std::size_t count) {
  const std::vector<std::string> parts = split(text, ',');
  std::vector<double> out(parts.size());
  bool ok = parts.size() == count;
  for (std::size_t i = 0; ok && i < parts.size(); ++i) ok = parseDouble(parts[i], out[i]);
  if (!ok)
    throw BadImpactInput(option + ": expected " + std::to_string(count) +
                         " comma-separated finite numbers, got '" + text + "'");
  return out;
}

SampleRange parseSampleRange(const std::string& option, const std::string& text) {
  const std::vector<std::string> parts = split(text, ':');
  SampleRange r{0.0, 0.0, 0};
  double n = 0.0;
  const bool ok = parts.size() == 3 && parseDouble(parts[0], r.a) && parseDouble(parts[1], r.b) &&
                  parseDouble(parts[2], n) && n >= 1.0 && n <= 100000.0 && n == std::floor(n);
  if (!ok)
    throw BadImpactInput(option + ": expected a:b:n (finite a, b; integer 1 <= n <= 100000), got '" +
                         text + "'");
  r.n = static_cast<int>(n);
  return r;
}

void requireFoot2OnGround(const Model& model, const Vec5& q) {
  const double z2 = pinnedTerms(model, q, Vec5(Vec5::Zero())).foot2(1);
  if (std::abs(z2) > 1e-9)
    throw BadImpactInput("--q: foot 2 height z2 = " + shortNumber(z2, "%.9g") +
                         " m; an impact needs foot 2 on the ground (|z2| <= 1e-9 m)");
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
