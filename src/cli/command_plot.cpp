// `gaitopt plot KIND RUN_DIR [--out FILE]`: runs the figure script scripts/plot/KIND.py with
// /usr/bin/python3 (Debian's matplotlib). The scripts read gaitopt's own outputs only; this
// command just finds them, so a new figure needs only a new script.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "data_files.hpp"
#include "gaitopt/io/output_transaction.hpp"

namespace gaitopt::cli {
namespace {

namespace fs = std::filesystem;

constexpr const char* kPython = "/usr/bin/python3";

struct PlotArgs {
  std::string kind, run_dir, out;
};

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// The figure's file: --out, else RUN_DIR/KIND.png (an input file: its name with .png, .gif for
// animate).
std::string figurePath(const PlotArgs& args) {
  if (!args.out.empty()) return args.out;
  std::error_code ec;
  if (fs::is_directory(args.run_dir, ec)) return (fs::path(args.run_dir) / (args.kind + ".png")).string();
  return fs::path(args.run_dir).replace_extension(args.kind == "animate" ? ".gif" : ".png").string();
}

// Runs the script without a shell (no quoting of user paths), the figure going to `staged`
// (GAITOPT_PLOT_OUT names its final place in the script's messages); its exit code is ours.
int runScript(const fs::path& script, const PlotArgs& args, const std::string& staged,
              const std::string& shown) {
  std::vector<std::string> argv{kPython, script.string(), args.run_dir, "--out", staged};
  std::vector<char*> cargv;
  for (std::string& a : argv) cargv.push_back(a.data());
  cargv.push_back(nullptr);
  std::cout.flush();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("plot: cannot start " + std::string(kPython));
  if (pid == 0) {
    setenv("GAITOPT_PLOT_OUT", shown.c_str(), 1);
    execv(kPython, cargv.data());
    std::cerr << "gaitopt plot: error: cannot run " << kPython
              << " (Debian: apt-get install python3-numpy python3-matplotlib)\n";
    _exit(kExitBadInput);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

}  // namespace

void registerPlotCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<PlotArgs>();
  CLI::App* cmd = app.add_subcommand(
      "plot",
      "Draw a figure from a run directory with scripts/plot/KIND.py (/usr/bin/python3, "
      "matplotlib): stick, torques, reactions, phase (a step run: summary.json + "
      "trajectory.csv) or sweep (sweep.csv); animate draws an export CSV (gaitopt export) as "
      "an animated GIF. Writes RUN_DIR/KIND.png unless --out is given. "
      "Scripts directory: $GAITOPT_PLOT_SCRIPTS, else gaitopt's scripts/plot (installed or the source tree).");
  cmd->add_option("kind", args->kind, "Figure: the name of a script in the scripts directory")
      ->required();
  cmd->add_option("run_dir", args->run_dir, "Directory written by gaitopt evaluate, optimize or sweep (animate: an export CSV)")
      ->required();
  cmd->add_option("--out", args->out,
                  "Output file, .png or .svg (.gif for animate; default RUN_DIR/KIND.png)")
      ->check(CLI::Validator(
          [](std::string& s) {
            const std::string ext = fs::path(s).extension().string();
            return ext == ".png" || ext == ".svg" || ext == ".gif"
                       ? std::string()
                       : "must end in .png or .svg (.gif for animate): " + s;
          },
          "FILE"));
  cmd->callback([args, &exit_code]() {
    const fs::path dir = scriptsDir();
    const std::vector<std::string> known = kinds(dir);
    if (known.empty())
      throw CLI::ValidationError("plot", "no figure scripts in " + dir.string() +
                                             " (set GAITOPT_PLOT_SCRIPTS to gaitopt's scripts/plot)");
    if (std::find(known.begin(), known.end(), args->kind) == known.end())
      throw CLI::ValidationError("KIND", "unknown figure '" + args->kind + "'; one of: " +
                                             joined(known) + " (scripts in " + dir.string() + ")");
    const std::string figure = figurePath(*args);
    OutputTransaction output({{"RUN_DIR", args->run_dir}});
    const std::string staged = output.file("--out", figure);
    exit_code = runScript(dir / (args->kind + ".py"), *args, staged, figure);
    if (exit_code == 0) output.commit();
  });
}

}  // namespace gaitopt::cli
