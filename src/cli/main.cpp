// gaitopt command-line entry point: a thin layer over libgaitopt.
#include <IpIpoptApplication.hpp>
#include <iostream>
#include <nlopt.hpp>

#include "commands.hpp"
#include "gaitopt_version.hpp"
#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/config_error.hpp"

namespace {

// An argument over 200 bytes is quoted by its first 200 printable ones, wherever a message
// (ours or CLI11's) echoes it.
std::string shortenedArguments(std::string message, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const std::string value = arg.compare(0, 2, "--") == 0 && arg.find('=') != std::string::npos
                                  ? arg.substr(arg.find('=') + 1)
                                  : arg;
    if (value.size() <= 200) continue;
    const std::string shown = gaitopt::printable(value);
    for (std::size_t at = message.find(value); at != std::string::npos;
         at = message.find(value, at + shown.size()))
      message.replace(at, value.size(), shown);
  }
  return message;
}

// Every message goes through printable(): input echoed back may hold control characters.
int fail(const std::string& message, int code, int argc, char** argv) {
  std::cerr << "gaitopt: error: "
            << gaitopt::printable(shortenedArguments(message, argc, argv), 4096) << "\n";
  return code;
}

// `--name=` with nothing after '=' (CLI11 would take the next word as the value).
std::string emptyOptionValue(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--") break;
    if (arg.size() > 3 && arg.compare(0, 2, "--") == 0 && arg.back() == '=' &&
        arg.find('=') == arg.size() - 1)
      return gaitopt::printable(arg) + ": empty value after '='";
  }
  return "";
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
  gaitopt::cli::registerLumpOsimCommand(app, exit_code);
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
  if (!unknown.empty())
    return fail(unknown + "; run with --help", gaitopt::cli::kExitBadInput, argc, argv);
  const std::string empty = emptyOptionValue(argc, argv);
  if (!empty.empty()) return fail(empty, gaitopt::cli::kExitBadInput, argc, argv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    return fail(std::string(e.what()) + "; run with --help for more information",
                gaitopt::cli::kExitBadInput, argc, argv);
  } catch (const gaitopt::ConfigError& e) {
    return fail(e.what(), gaitopt::cli::kExitBadInput, argc, argv);
  } catch (const gaitopt::OutputError& e) {
    return fail(e.what(), gaitopt::cli::kExitBadInput, argc, argv);
  } catch (const std::exception& e) {
    return fail(e.what(), 1, argc, argv);
  }
  return exit_code;
}
