#pragma once
// Each `gaitopt` subcommand registers itself on the application; its callback stores the
// process exit code. Exit codes: 0 success, 2 bad input, 3 step undefined / request infeasible.
#include <CLI/CLI.hpp>

namespace gaitopt::cli {

constexpr int kExitBadInput = 2;
constexpr int kExitUndefined = 3;

void registerModelCommand(CLI::App& app, int& exit_code);
void registerEvaluateCommand(CLI::App& app, int& exit_code);
void registerOptimizeCommand(CLI::App& app, int& exit_code);
void registerSweepCommands(CLI::App& app, int& exit_code);  // sweep, sweep-merge
void registerImportOpenSimCommand(CLI::App& app, int& exit_code);
void registerLumpOsimCommand(CLI::App& app, int& exit_code);
void registerExportCommand(CLI::App& app, int& exit_code);
void registerExportModelCommand(CLI::App& app, int& exit_code);
void registerSimulateCommand(CLI::App& app, int& exit_code);
void registerStabilityCommand(CLI::App& app, int& exit_code);
void registerImpactCommand(CLI::App& app, int& exit_code);
void registerImpactMapCommand(CLI::App& app, int& exit_code);
void registerPlotCommand(CLI::App& app, int& exit_code);
void registerSynthCommand(CLI::App& app, int& exit_code);
void registerDiagnoseCommand(CLI::App& app, int& exit_code);

}  // namespace gaitopt::cli
