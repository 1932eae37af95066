// `gaitopt diagnose`: what the model gets wrong on measured data, the cause, the extended model
// and its gain on held-out steps.
#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gaitopt/ident/diagnose.hpp"
#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/diagnosis_file.hpp"
#include "gaitopt/io/measured_data.hpp"
#include "gaitopt/io/robot_file.hpp"

namespace gaitopt::cli {
namespace {

struct DiagnoseArgs {
  std::string robot, data, out, effects;
  int holdout = 3, holdout_shift = 0;
  bool quiet = false;
};

std::vector<EffectKind> parseKinds(const std::string& list) {
  std::vector<EffectKind> kinds;
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    bool found = false;
    for (int k = 0; k < kNumEffectKinds; ++k)
      if (name == effectInfo(static_cast<EffectKind>(k)).name) {
        kinds.push_back(static_cast<EffectKind>(k));
        found = true;
      }
    if (!found) throw CLI::ValidationError("--effects", "unknown effect '" + printable(name) + "'");
  }
  return kinds;
}

}  // namespace

void registerDiagnoseCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<DiagnoseArgs>();
  CLI::App* cmd = app.add_subcommand(
      "diagnose",
      "Compare a robot model with measured walking data: residuals, the significant cause(s), "
      "an extended robot file and its gain on held-out steps. Writes DIR/{diagnosis.json, "
      "residuals.csv, report.md, extended_robot.yaml}. Exit 2: bad input (nothing written).");
  cmd->add_option("--robot", args->robot, "Nominal robot YAML file")->required();
  cmd->add_option("--data", args->data, "Measured-data CSV file")->required();
  cmd->add_option("--out", args->out, "Output directory (created if missing)")->required();
  cmd->add_option("--holdout", args->holdout, "Hold out every K-th step (K >= 2, default 3)")
      ->check(integerWithin(2, 1000000));
  cmd->add_option("--holdout-shift", args->holdout_shift,
                  "Shift the held-out steps by S (0 <= S < K; with K = 2, 0 and 1 swap the fit "
                  "and held-out halves)")
      ->check(integerWithin(0, 1000000));
  cmd->add_option("--effects", args->effects,
                  "Comma-separated candidate effects (default: all), e.g. coulomb,viscous");
  cmd->add_flag("--quiet", args->quiet, "No progress lines");
  cmd->callback([args, &exit_code]() {
    DiagnoseOptions options;
    const auto start = std::chrono::steady_clock::now();
    if (!args->quiet)
      options.on_progress = [start](const std::string& stage, int done, int total) {
        const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
        std::cout << "diagnose [" << done << "/" << total << "] " << stage << "  "
                  << elapsedAndRemaining(elapsed.count(), done, total) << "\n"
                  << std::flush;
      };
    options.holdout = args->holdout;
    options.holdout_shift = args->holdout_shift;
    if (!args->effects.empty()) options.kinds = parseKinds(args->effects);
    const RobotParams robot = loadRobot(args->robot);
    const MeasuredData data = readMeasuredCsv(args->data);
    requirePlausibleTorques(data, robot, args->data);
    OutputTransaction output({{"--robot", args->robot}, {"--data", args->data}});
    const std::string dir = output.directory("--out", args->out, ourFiles(diagnosisFileNames()));
    Diagnosis d;
    try {
      d = diagnose(robot, ModelOptions{}, data, options);
    } catch (const std::invalid_argument& e) {
      throw CLI::ValidationError("--holdout", e.what());
    }
    const DiagnosisDocuments documents = diagnosisDocuments(args->robot, data, d);
    writeDiagnosisFiles(dir, documents);
    output.commit();
    const std::string& report = documents.report;
    const std::size_t first = report.find("\n\n") + 2;  // the sentence after the title
    std::cout << report.substr(first, report.find('\n', first) - first) << "\n";
    exit_code = 0;
  });
}

}  // namespace gaitopt::cli
