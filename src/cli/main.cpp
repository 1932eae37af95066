// gaitopt command-line entry point: a thin layer over libgaitopt.
#include <IpIpoptApplication.hpp>
#include <iostream>
#include <nlopt.hpp>

#include "commands.hpp"
#include "gaitopt_version.hpp"
#include "gaitopt/io/atomic_file.hpp"
#include "gaitopt/io/config_error.hpp"

namespace {

// Every message goes through printable(): input echoed back may hold control characters.
int fail(const std::string& message, int code) {
  std::cerr << "gaitopt: error: " << gaitopt::printable(message, 4096) << "\n";
  return code;
}

// CLI11 reports an unknown first word as a missing subcommand; name it instead.
std::string unknownSubcommand(const CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return "";
  std::string names;
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (sub->get_name() == argv[1]) return "";
    names += (names.empty() ? "" : ", ") + sub->get_name();
  }
  return "unknown subcommand '" + std::string(argv[1]) + "' (expected one of: " + names + ")";
}

}  // namespace

int main(int argc, char** argv) {
  gaitopt::removeTemporariesOnInterrupt();  // before any thread starts
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
  const std::string unknown = unknownSubcommand(app, argc, argv);
  if (!unknown.empty()) return fail(unknown + "; run with --help", gaitopt::cli::kExitBadInput);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    return fail(std::string(e.what()) + "; run with --help for more information",
                gaitopt::cli::kExitBadInput);
  } catch (const gaitopt::ConfigError& e) {
    return fail(e.what(), gaitopt::cli::kExitBadInput);
  } catch (const gaitopt::OutputError& e) {
    return fail(e.what(), gaitopt::cli::kExitBadInput);
  } catch (const std::exception& e) {
    return fail(e.what(), 1);
  }
  return exit_code;
}
