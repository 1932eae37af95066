// `gaitopt import-opensim` on the shipped trial: the CSV at the GRF rate, the analysis report,
// and bad input exiting 2 with nothing written.
#include <catch2/catch.hpp>

#include <filesystem>

#include "test_opensim_data.hpp"

using namespace gaitopt::test;
using Catch::Matchers::Contains;

TEST_CASE("import-opensim CLI: CSV at the GRF rate; bad input exits 2 writing nothing",
          "[opensim_import]") {
  ScratchDir dir("import_opensim");
  const std::string out = dir.fresh("data") + ".csv";
  const std::string base = "import-opensim --ik " + quoted(opensimIk()) + " --grf " + quoted(opensimGrf());
  const CliRun ok = runCli(base + " --trc " + quoted(opensimTrc()) + " --out " + quoted(out));
  REQUIRE(ok.exit_code == 0);
  CHECK_THAT(ok.out, Contains("belt speed 1.12") && Contains("(heel markers)"));
  const std::vector<std::string> rows = fileLines(out);
  REQUIRE(rows.size() == 1502);
  CHECK(rows[0] == "t,alpha,delta1,delta2,delta3,delta4,phase,stance,step,R1x,R1z,R2x,R2z");
  CHECK_THAT(rows[1], Contains(",DS,left,0,17.26938127,20.49185173,101.5119767,745.4661142"));
  CHECK(rows[1].rfind("0,", 0) == 0);
  CHECK(rows[1501].rfind("2.5,", 0) == 0);
  CHECK_THAT(rows[1501], Contains(",DS,left,4,"));
  const std::string report = dir.fresh("report") + ".json";
  const CliRun analysed = runCli(base + " --id " + quoted(opensimId()) + " --out " + quoted(out) +
                                 " --report " + quoted(report));
  REQUIRE(analysed.exit_code == 0);
  CHECK_THAT(analysed.out, Contains("(IK ankle)") && Contains("knee_right: RMS difference to OpenSim"));
  CHECK_THAT(readFile(report), Contains("\"joint\": \"knee_left\"") && Contains("\"radius_all\"") &&
                                   Contains("\"stances\"") && Contains("\"side\": \"right\""));

  const std::vector<std::string> grf = fileLines(opensimGrf());
  const std::string bad = writeDamaged(dir, grf, {{500, grf[499] + "\tx"}}, ".mot");
  const std::string out2 = dir.fresh("data") + ".csv";
  const CliRun run = runCli("import-opensim --ik " + quoted(opensimIk()) + " --grf " + quoted(bad) +
                            " --out " + quoted(out2));
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Contains(bad + ":500: row has 20 fields, expected 19"));
  CHECK_FALSE(std::filesystem::exists(out2));
}
