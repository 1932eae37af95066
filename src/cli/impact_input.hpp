#pragma once
// Input checks shared by `gaitopt impact` and `gaitopt impact-map`; each throws BadImpactInput
// with a message naming the option or quantity at fault (exit 2).
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gaitopt/impact/impact_result.hpp"

namespace gaitopt::cli {

struct BadImpactInput : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `count` comma-separated finite numbers given to `option`.
std::vector<double> parseNumberList(const std::string& option, const std::string& text,
                                    std::size_t count);

// "a:b:n" given to `option`: finite a, b and an integer n >= 1.
struct SampleRange {
  double a, b;
  int n;
};
SampleRange parseSampleRange(const std::string& option, const std::string& text);

// The configuration `command` uses: q with foot 2 projected onto the ground (a note on standard
// error when it moved), or BadImpactInput when foot 2 is more than kFoot2HeightTolerance off it.
constexpr double kFoot2HeightTolerance = 1e-5;  // [m]: six printed decimals of the angles
Vec5 foot2OnGround(const Model& model, const Vec5& q, const char* command);

ImpactModelKind parseImpactModel(const std::string& text);

// μ must be finite and >= 0.
void requireFriction(const std::string& option, double mu);

// run() (which returns the exit code); a BadImpactInput becomes "gaitopt <command>: error: ..."
// on standard error and exit 2.
int exitCodeOf(const char* command, const std::function<int()>& run);

}  // namespace gaitopt::cli
