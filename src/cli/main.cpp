// gaitopt command-line entry point: a thin layer over libgaitopt.
#include <IpIpoptApplication.hpp>
#include <iostream>
#include <nlopt.hpp>

#include "commands.hpp"
#include "gaitopt_version.hpp"
#include "gaitopt/io/config_error.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "gaitopt: optimal walking gaits for RABBIT-class planar bipeds (five links, point feet,\n"
      "four actuated joints), after S. Miossec's 2004 thesis."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "gaitopt " GAITOPT_VERSION " (" GAITOPT_GIT_DESCRIBE ")");
  int exit_code = 0;
  gaitopt::cli::registerModelCommand(app, exit_code);
  gaitopt::cli::registerEvaluateCommand(app, exit_code);
  gaitopt::cli::registerOptimizeCommand(app, exit_code);
  gaitopt::cli::registerSweepCommands(app, exit_code);
  gaitopt::cli::registerImportOpenSimCommand(app, exit_code);
  gaitopt::cli::registerExportCommand(app, exit_code);
  gaitopt::cli::registerExportModelCommand(app, exit_code);
  gaitopt::cli::registerSimulateCommand(app, exit_code);
  gaitopt::cli::registerStabilityCommand(app, exit_code);
  gaitopt::cli::registerImpactCommand(app, exit_code);
  gaitopt::cli::registerImpactMapCommand(app, exit_code);
  gaitopt::cli::registerPlotCommand(app, exit_code);
  gaitopt::cli::registerSynthCommand(app, exit_code);
  gaitopt::cli::registerDiagnoseCommand(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : gaitopt::cli::kExitBadInput;
  } catch (const gaitopt::ConfigError& e) {
    std::cerr << "gaitopt: error: " << e.what() << "\n";
    return gaitopt::cli::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "gaitopt: error: " << e.what() << "\n";
    return 1;
  }
  return exit_code;
}
