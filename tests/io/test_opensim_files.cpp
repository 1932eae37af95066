// Readers of OpenSim .mot/.sto and .trc files: the shipped trial parses to the documented
// shapes and values; damaged copies fail with the file, column and line.
#include <catch2/catch.hpp>

#include "gaitopt/io/opensim_table.hpp"
#include "gaitopt/io/opensim_trial_file.hpp"
#include "gaitopt/io/tab_text.hpp"
#include "gaitopt/io/trc_file.hpp"
#include "gaitopt/math/decimal.hpp"
#include "test_opensim_data.hpp"

using namespace gaitopt;
using namespace gaitopt::test;
using Catch::Matchers::Contains;

TEST_CASE("shipped GRF, IK and ID tables parse to the documented shapes and values",
          "[opensim_io]") {
  const OpenSimTable grf = readOpenSimTable(opensimGrf());
  CHECK(grf.rows() == 1501);
  CHECK(grf.columns.size() == 19);
  CHECK(grf.in_degrees);
  CHECK(grf.values(0, 0) == 0.0);
  CHECK(grf.column("ground_force_vy")(0) == Approx(745.4661142).epsilon(1e-12));
  CHECK(grf.column("1_ground_force_px")(0) == Approx(0.81009656).epsilon(1e-12));
  CHECK(grf.time()(1500) == 2.5);
  CHECK(grf.column("1_ground_force_vy")(1500) == Approx(172.6907879).epsilon(1e-12));
  CHECK(grf.column("ground_force_py").cwiseEqual(-0.0075).all());

  const OpenSimTable ik = readOpenSimTable(opensimIk());
  CHECK(ik.rows() == 151);
  CHECK(ik.columns.size() == 11);
  CHECK(ik.in_degrees);
  CHECK(ik.column("pelvis_tilt")(0) == Approx(10.32995988).epsilon(1e-12));
  CHECK(ik.column("lumbar_extension")(150) == Approx(-15.92098183).epsilon(1e-12));
  CHECK(ik.time()(150) == 2.5);

  const OpenSimTable id = readOpenSimTable(opensimId());
  CHECK(id.rows() == 151);
  CHECK_FALSE(id.in_degrees);
  CHECK(id.time()(0) == Approx(-5.0e-7).margin(1e-15));
  CHECK(id.column("hip_flexion_r_moment")(0) == Approx(16.77513537).epsilon(1e-12));
  CHECK(id.column("lumbar_extension_moment")(150) == Approx(3.88919711).epsilon(1e-12));
  REQUIRE_THROWS_WITH(id.column("ankle_moment"), Contains("ankle_moment") && Contains("missing"));
}

TEST_CASE("shipped marker file parses to metres with 41 markers and 151 frames", "[opensim_io]") {
  const TrcData trc = readTrcFile(opensimTrc());
  CHECK(trc.rate == 60.0);
  CHECK(trc.markers.size() == 41);
  CHECK(trc.markers.front() == "R.ASIS");
  CHECK(trc.markers.back() == "Top.Head");
  CHECK(trc.time.size() == 151);
  CHECK(trc.time(150) == 2.5);
  CHECK(trc.marker("R.ASIS")(0, 0) == Approx(0.61724762).epsilon(1e-12));
  CHECK(trc.marker("R.ASIS")(0, 1) == Approx(1.05527502).epsilon(1e-12));
  CHECK(trc.marker("R.ASIS")(150, 0) == Approx(0.59761365).epsilon(1e-12));
  REQUIRE_THROWS_WITH(trc.marker("Nose"), Contains("Nose") && Contains("missing"));
}

TEST_CASE("damaged .mot files are refused naming file, column and line", "[opensim_io]") {
  ScratchDir dir("opensim_io");
  const std::vector<std::string> lines = fileLines(opensimGrf());
  const auto load = [](const std::string& p) { return readOpenSimTable(p); };
  // Line 8 is the first data row; its 4th field (ground_force_vz) replaced.
  std::string row8 = lines[7];
  const auto field4 = [&](const std::string& with) {
    std::vector<std::string> f;
    std::istringstream s(row8);
    for (std::string x; std::getline(s, x, '\t');) f.push_back(x);
    f[3] = with;
    std::string out;
    for (std::size_t k = 0; k < f.size(); ++k) out += (k ? "\t" : "") + f[k];
    return out;
  };
  SECTION("truncated file: fewer rows than nRows") {
    const std::string p = writeDamaged(dir, lines, {}, ".mot", 1000);
    requireRowError(load, p, 1000, "the file has 993 data rows but its header says nRows=1501");
  }
  SECTION("truncated row") {
    const std::string p = writeDamaged(dir, lines, {{20, lines[19].substr(0, 40)}}, ".mot");
    requireRowError(load, p, 20, "row has 4 fields, expected 19");
  }
  SECTION("non-numeric value") {
    const std::string p = writeDamaged(dir, lines, {{8, field4("abc")}}, ".mot");
    requireConfigError(load, p, "ground_force_vz", 8, "not a finite number: 'abc'");
  }
  SECTION("NaN") {
    const std::string p = writeDamaged(dir, lines, {{8, field4("nan")}}, ".mot");
    requireConfigError(load, p, "ground_force_vz", 8, "not a finite number");
  }
  SECTION("no endheader") {
    const std::string p = writeDamaged(dir, lines, {{6, "#"}}, ".mot");
    REQUIRE_THROWS_WITH(load(p), Contains(p) && Contains("no 'endheader' line"));
  }
  SECTION("absurd row count in the header") {
    const std::string p = writeDamaged(dir, lines, {{3, "nRows=1e300"}}, ".mot");
    requireConfigError(load, p, "nRows", 3, "must be a non-negative integer");
  }
  SECTION("missing inDegrees: read with the units undeclared; a malformed one refused") {
    const std::string p = writeDamaged(dir, lines, {{5, "#"}}, ".mot");
    CHECK_FALSE(load(p).units_declared);
    CHECK(load(opensimGrf()).units_declared);
    const std::string q = writeDamaged(dir, lines, {{5, "inDegrees=maybe"}}, ".mot");
    requireConfigError(load, q, "inDegrees", 5, "must be 'yes' or 'no', got 'maybe'");
  }
  SECTION("time going backwards") {
    const std::string p = writeDamaged(dir, lines, {{9, lines[7]}}, ".mot");
    requireConfigError(load, p, "time", 9, "does not increase strictly");
  }
  SECTION("duplicate column") {
    const std::string p = writeDamaged(
        dir, lines, {{7, replacedOnce(lines[6], "ground_force_vz", "ground_force_vy")}}, ".mot");
    requireConfigError(load, p, "ground_force_vy", 7, "duplicate column name");
  }
}

TEST_CASE("damaged .trc files are refused naming file, column and line", "[opensim_io]") {
  ScratchDir dir("opensim_trc");
  const std::vector<std::string> lines = fileLines(opensimTrc());
  const auto load = [](const std::string& p) { return readTrcFile(p); };
  SECTION("truncated file") {
    const std::string p = writeDamaged(dir, lines, {}, ".trc", 100);
    requireConfigError(load, p, "NumFrames", 100, "header says NumFrames=151");
  }
  SECTION("NumFrames far beyond the file: refused as truncated, nothing allocated for it") {
    const std::string p =
        writeDamaged(dir, lines, {{3, replacedOnce(lines[2], "151", "1000000000000")}}, ".trc");
    REQUIRE_THROWS_WITH(load(p), Contains(p + ":") &&
                                     Contains("151 frames but its header says NumFrames=1000000000000"));
  }
  SECTION("wrong first line") {
    const std::string p = writeDamaged(dir, lines, {{1, "Frame\tTime"}}, ".trc");
    REQUIRE_THROWS_WITH(load(p), Contains(p + ":1: ") && Contains("PathFileType"));
  }
  SECTION("row with a missing marker coordinate") {
    std::string row = lines[6];
    row = row.substr(0, row.rfind('\t', row.size() - 2));  // drop the last value
    const std::string p = writeDamaged(dir, lines, {{7, row}}, ".trc");
    requireRowError(load, p, 7, "row has 124 fields, expected 125");
  }
  SECTION("occluded (empty) value") {
    std::string row = lines[6];
    const std::size_t a = row.find('\t', row.find('\t') + 1);  // after Time
    const std::size_t b = row.find('\t', a + 1);
    row = row.substr(0, a + 1) + row.substr(b);
    const std::string p = writeDamaged(dir, lines, {{7, row}}, ".trc");
    requireConfigError(load, p, "R.ASIS.X", 7, "empty value");
  }
  SECTION("non-numeric time") {
    const std::string p = writeDamaged(dir, lines, {{7, replacedOnce(lines[6], "0.000000", "t0")}}, ".trc");
    requireConfigError(load, p, "Time", 7, "not a finite number: 't0'");
  }
  SECTION("units other than mm or m") {
    const std::string p = writeDamaged(dir, lines, {{3, replacedOnce(lines[2], "mm", "cm")}}, ".trc");
    requireConfigError(load, p, "Units", 3, "must be 'mm' or 'm'");
  }
  SECTION("millimetre data declared as metres") {
    const std::string p = writeDamaged(dir, lines, {{3, replacedOnce(lines[2], "mm", "m")}}, ".trc");
    try {
      load(p);
      FAIL("no ConfigError");
    } catch (const ConfigError& e) {
      CHECK(e.line() == 7);  // the first frame
      CHECK_THAT(std::string(e.what()), Contains(" m lies beyond 50 m of the origin: check the "
                                                 "header's Units (millimetres declared as m?)"));
    }
  }
  SECTION("metre data declared as millimetres") {
    std::vector<std::string> metres = lines;
    for (std::size_t i = 5; i < metres.size(); ++i) {
      std::vector<std::string> f = splitTabFields(metres[i], "", 0);
      if (f.size() < 3) continue;
      std::string row = f[0] + "\t" + f[1];
      for (std::size_t c = 2; c < f.size(); ++c)
        row += "\t" + formatDouble(std::stod(f[c]) * 1e-3);
      metres[i] = row;
    }
    const std::string p = writeDamaged(dir, metres, {}, ".trc");
    requireConfigError(load, p, "Units", 3,
                       "every marker lies within 0.05 m of the origin: check the header's Units "
                       "(metres declared as mm?)");
  }
}

TEST_CASE("an IK file's inDegrees flag is checked against its angles", "[opensim_io]") {
  ScratchDir dir("opensim_units");
  const std::vector<std::string> lines = fileLines(opensimIk());
  const auto recording = [&](const std::string& ik) {
    return readOpenSimRecording({ik, opensimGrf(), ""});
  };
  // Degrees declared as radians: pelvis_tilt 10.33 "rad" on the first data row.
  const std::string no = writeDamaged(dir, lines, {{5, "inDegrees=no"}}, ".mot");
  requireConfigError(recording, no, "pelvis_tilt", 12,
                     "angle 10.33 rad with inDegrees=no is beyond half a turn: degrees declared "
                     "as radians?");
  // Radians declared as degrees: every angle column converted to radians, the flag kept.
  std::vector<std::string> radians = lines;
  for (std::size_t i = 11; i < radians.size(); ++i) {
    std::vector<std::string> f = splitTabFields(radians[i], "", 0);
    std::string row = f[0];
    for (std::size_t c = 1; c < f.size(); ++c)
      row += "\t" + (c == 2 || c == 3 ? f[c] : formatDouble(std::stod(f[c]) * M_PI / 180.0));
    radians[i] = row;
  }
  requireConfigError(recording, writeDamaged(dir, radians, {}, ".mot"), "knee_angle_r", 12,
                     "the knee moves by less than 10 degrees over the trial with inDegrees=yes: "
                     "radians declared as degrees?");
  CHECK_NOTHROW(recording(opensimIk()));
}
