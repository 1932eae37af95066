// `gaitopt import-opensim` on both shipped trials: the CSV at the GRF rate, the result folder
// with the analysis report, the conventions stated, the sanity checks, and bad input exiting 2
// with nothing written.
#include <catch2/catch.hpp>

#include <filesystem>

#include "gaitopt/io/tab_text.hpp"
#include "test_opensim_data.hpp"

using namespace gaitopt::test;
using Catch::Matchers::Contains;

TEST_CASE("import-opensim CLI: CSV at the GRF rate, bad input exits 2 writing nothing",
          "[opensim_import]") {
  ScratchDir dir("import_opensim");
  const std::string out = dir.fresh("data") + ".csv";
  const std::string base = "import-opensim --ik " + quoted(opensimIk()) + " --grf " + quoted(opensimGrf());
  const CliRun ok = runCli(base + " --trc " + quoted(opensimTrc()) + " --out " + quoted(out));
  REQUIRE(ok.exit_code == 0);
  CHECK_THAT(ok.out, Contains("belt speed 1.12") && Contains("(heel markers)") &&
                         Contains("force plates: right 'ground_force_', left '1_ground_force_'") &&
                         Contains("knee flexion: knee_angle negative"));
  const std::vector<std::string> rows = fileLines(out);
  REQUIRE(rows.size() == 1502);
  CHECK(rows[0] == "t,alpha,delta1,delta2,delta3,delta4,phase,stance,step,R1x,R1z,R2x,R2z,cop1x,cop2x");
  CHECK_THAT(rows[1], Contains(",DS,left,0,17.26938127,20.49185173,101.5119767,745.4661142,"));
  CHECK(rows[1].rfind("0,", 0) == 0);
  CHECK(rows[1501].rfind("2.5,", 0) == 0);
  CHECK_THAT(rows[1501], Contains(",DS,left,4,"));
  const std::string result = dir.fresh("result");
  const CliRun analysed = runCli(base + " --id " + quoted(opensimId()) + " --result " + quoted(result));
  REQUIRE(analysed.exit_code == 0);
  CHECK_THAT(analysed.out, Contains("(IK ankle)") && Contains("knee_right: RMS difference to OpenSim") &&
                               Contains("whole-body force balance residual RMS"));
  CHECK(fileLines(result + "/data.csv").size() == 1502);
  CHECK_THAT(readFile(result + "/report.json"),
             Contains("\"joint\": \"knee_left\"") && Contains("\"radius_all\"") && Contains("\"stances\"") &&
                 Contains("\"side\": \"right\"") && Contains("\"conventions\": [\"force plates: right"));

  const std::vector<std::string> grf = fileLines(opensimGrf());
  const std::string bad = writeDamaged(dir, grf, {{500, grf[499] + "\tx"}}, ".mot");
  const std::string out2 = dir.fresh("data") + ".csv";
  const CliRun run = runCli("import-opensim --ik " + quoted(opensimIk()) + " --grf " + quoted(bad) +
                            " --out " + quoted(out2));
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Contains(bad + ":500: row has 20 fields, expected 19"));
  CHECK_FALSE(std::filesystem::exists(out2));
}

TEST_CASE("import-opensim CLI: the second trial, its conventions and the sanity checks",
          "[opensim_import]") {
  ScratchDir dir("import_rajagopal");
  const std::string base = "import-opensim --ik " + quoted(rajagopalIk()) + " --grf " + quoted(rajagopalGrf()) +
                           " --trc " + quoted(rajagopalTrc()) + " --robot " + quoted(rajagopalRobot());
  const std::string result = dir.fresh("result");
  const CliRun ok = runCli(base + " --model " + quoted(rajagopalModel()) + " --id " + quoted(rajagopalId()) +
                           " --time-window 0.5:1.75 --result " + quoted(result));
  REQUIRE(ok.exit_code == 0);
  CHECK_THAT(ok.out, Contains("force plates: right 'ground_force_r_', left 'ground_force_l_' (detected "
                              "from the column names)") &&
                         Contains("knee flexion: knee_angle positive (model ") &&
                         Contains("pelvis markers: R.ASIS, L.ASIS, S2 (detected)") &&
                         Contains("stance heel speed after belt removal: median 0.0"));
  CHECK(ok.err.find("WARNING") == std::string::npos);
  const std::vector<std::string> rows = fileLines(result + "/data.csv");
  CHECK(rows[1].rfind("0.5,", 0) == 0);
  CHECK(rows.back().rfind("1.75,", 0) == 0);

  // A reference whose knee moments have the other sign: refused, nothing written.
  std::vector<std::string> id = fileLines(opensimId());
  for (std::size_t i = 7; i < id.size(); ++i) {
    std::vector<std::string> f = gaitopt::splitTabFields(id[i], "", 0);
    std::string row = f[0];
    for (std::size_t c = 1; c < f.size(); ++c)
      row += "\t" + (c != 5 ? f[c] : f[c][0] == '-' ? f[c].substr(1) : "-" + f[c]);
    id[i] = row;
  }
  const std::string flipped = writeDamaged(dir, id, {}, ".sto");
  const std::string out = dir.fresh("data") + ".csv";
  const CliRun wrong = runCli("import-opensim --ik " + quoted(opensimIk()) + " --grf " + quoted(opensimGrf()) +
                              " --id " + quoted(flipped) + " --out " + quoted(out));
  CHECK(wrong.exit_code == 2);
  CHECK_THAT(wrong.err, Contains(flipped) && Contains("knee_right moment correlates negatively") &&
                            Contains("a sign convention is wrong"));
  CHECK_FALSE(std::filesystem::exists(out));

  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {" --out " + quoted(out) + " --result " + quoted(out + ".d"), "excludes"},
           {"", "give one: --out DATA.csv or --result DIR"},
           {" --time-window 1.5:0.9 --out " + quoted(out), "START < END"},
           {" --time-window 3:4 --out " + quoted(out), "fewer than 3 force-plate samples"}}) {
    const CliRun bad = runCli(base + args);
    INFO(args);
    CHECK(bad.exit_code == 2);
    CHECK_THAT(bad.err, Contains(message));
    CHECK_FALSE(std::filesystem::exists(out));
  }
}
