// SPDX-License-Identifier: MIT
// The files tumble writes, read by other programs' readers: JSON (nlohmann
// and Python's json), CSV (numpy.genfromtxt(names=True) and pandas.read_csv,
// called as they are), the compressed binary .vtu (VTK's own reader) and
// extended XYZ.
//
// Python is /usr/bin/python3 with numpy, pandas and VTK, which
// scripts/install-deps.sh installs: their absence is a failure, not a skip.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "io/json.hpp"
#include "io/sweep.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using tumble::io::Json;
using tumble::test_support::read_file;
using tumble::test_support::run_command;

namespace {

class Formats : public tumble::test_support::ScratchTest {
protected:
    // Runs `script` with /usr/bin/python3 and `arguments` (quoted by the caller).
    tumble::test_support::CommandResult python(const std::string& script, const std::string& arguments) {
        const fs::path file = write("check.py", script);
        return run_command("/usr/bin/python3 " + file.string() + " " + arguments);
    }
};

// A path in single quotes for the shell (the paths here hold no single quote).
std::string quoted(const fs::path& p) {
    std::string q = p.string();
    q.insert(q.begin(), '\'');
    q.push_back('\'');
    return q;
}

std::string tumble(const std::string& arguments) { return std::string(TUMBLE_BINARY) + " " + arguments; }

// ---- JSON ------------------------------------------------------------------

TEST_F(Formats, JsonRoundTripsQuotesBackslashesControlCharactersAndNaN) {
    const std::string name = "q\"uote\\back\tslash\n\x01 \xc3\xa9.toml";
    const Json j{{"file", name},
                 {"nan", std::numeric_limits<double>::quiet_NaN()},
                 {"inf", -std::numeric_limits<double>::infinity()},
                 {"x", 0.1},
                 {"big", std::numeric_limits<std::int64_t>::max()}};
    const fs::path file = dir_ / "a.json";
    tumble::io::write_json_file(file, j);
    const Json back = tumble::io::parse_json(read_file(file), file.string());
    EXPECT_EQ(back.at("file").get<std::string>(), name);
    // JSON has no NaN or infinity: both are written as null and read as undefined.
    EXPECT_TRUE(back.at("nan").is_null());
    EXPECT_TRUE(back.at("inf").is_null());
    EXPECT_EQ(tumble::io::json_number(back, "nan"), std::nullopt);
    EXPECT_EQ(back.at("x").get<double>(), 0.1);  // written so that it reads back to the same double
    EXPECT_EQ(back.at("big").get<std::int64_t>(), std::numeric_limits<std::int64_t>::max());  // an integer stays exact

    // Python's reader agrees: the same name, null as None.
    const auto r = python(R"(
import json, sys
d = json.load(open(sys.argv[1], encoding="utf-8"))
open(sys.argv[2], "w", encoding="utf-8", newline="").write(d["file"])
print(d["nan"], d["inf"], repr(d["x"]), d["big"])
)",
                          quoted(file) + " " + quoted(dir_ / "name.txt"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output, "None None 0.1 9223372036854775807\n");
    EXPECT_EQ(read_file(dir_ / "name.txt"), name);
}

// A run whose scenario file and output directory have a quote, a backslash
// and a blank in their names: run.json names the file exactly, and it and
// tumble contact --json parse with nlohmann and with Python.
TEST_F(Formats, EveryJsonOfARunWithAQuoteInItsNameParses) {
    const fs::path scenario =
        write("q\"uote\\ run.toml", tumble::test_support::walled_box_scenario("0.002", "seed = 5\n"));
    const fs::path out = dir_ / "out \"q\\";
    const auto run = run_command(tumble("run -q " + quoted(scenario) + " --out " + quoted(out)));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const Json j = tumble::io::parse_json(read_file(out / "run.json"), "run.json");
    EXPECT_EQ(j.at("scenario").get<std::string>(), scenario.string());
    EXPECT_EQ(j.at("seed").get<int>(), 5);
    EXPECT_GT(j.at("steps").get<std::int64_t>(), 0);
    // Where the time went: every step counted, the shares of the wall time within 1.
    const Json& phases = j.at("time_by_phase");
    EXPECT_EQ(phases.at("steps").get<std::int64_t>(), j.at("steps").get<std::int64_t>());
    double shares = 0.0;
    for (const char* phase : {"forces", "neighbours", "motion", "exchange", "other"})
        shares += phases.at("phases").at(phase).at("share").get<double>();
    EXPECT_NEAR(shares, 1.0, 0.01);

    const auto contact = run_command(tumble("contact " + quoted(scenario) + " --speeds 0.5 --json"));
    ASSERT_EQ(contact.exit_code, 0) << contact.output;
    std::ofstream(dir_ / "contact.json") << contact.output;
    EXPECT_EQ(tumble::io::parse_json(contact.output, "contact").at("pairs").size(), 2u);  // m-m, m-flat wall

    const auto r = python(R"(
import json, sys
run = json.load(open(sys.argv[1], encoding="utf-8"))
contact = json.load(open(sys.argv[2], encoding="utf-8"))
print(run["scenario"] == sys.argv[3], len(contact["pairs"]))
)",
                          quoted(out / "run.json") + " " + quoted(dir_ / "contact.json") + " " + quoted(scenario));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output, "True 2\n");
}

// ---- CSV -------------------------------------------------------------------

// Loads every CSV of a run directory (and its snapshots) with numpy and
// pandas as a user would, without options, and prints per file whether
// each reader saw the header's column names and every row.
const char* csv_check = R"(
import glob, os, sys
import numpy as np
import pandas as pd

run = sys.argv[1]
for path in sorted(glob.glob(os.path.join(run, "*.csv")) + glob.glob(os.path.join(run, "snapshots", "*.csv"))):
    with open(path) as f:
        header = f.readline().rstrip("\n").split(",")
        rows = sum(1 for line in f if line.strip())
    a = np.atleast_1d(np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="utf-8"))
    d = pd.read_csv(path)
    print(os.path.relpath(path, run), "numpy", list(a.dtype.names) == header and len(a) == rows,
          "pandas", list(d.columns) == header and len(d) == rows, "duplicate_rows", int(d.duplicated().sum()))
)";

void expect_all_loaded(const std::string& output, const std::vector<std::string>& files) {
    for (const std::string& f : files)
        EXPECT_NE(output.find(f + " numpy True pandas True duplicate_rows 0\n"), std::string::npos) << f << "\n"
                                                                                                    << output;
    EXPECT_EQ(output.find(" False "), std::string::npos) << output;
}

TEST_F(Formats, CsvFilesOfARunLoadWithNumpyAndPandasAsTheyAre) {
    const fs::path scenario = write(
        "s.toml", tumble::test_support::walled_box_scenario(
                      "0.002", "", "[output]\ndirectory = \"out\"\nsnapshot_interval = 0.001\ntime_series_interval = 0.0005\n"));
    const auto run = run_command(tumble("run -q " + quoted(scenario) + " --out " + quoted(dir_ / "run")));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const auto r = python(csv_check, quoted(dir_ / "run"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    expect_all_loaded(r.output, {"time_series.csv", "snapshots/000000.csv", "snapshots/000001.csv"});
}

// A short drum (material names with '-' in the column names), analysed
// from N = 0 so that every analysis table is written. time_series.csv has
// no repeated row (it had the start of the rotation twice).
TEST_F(Formats, CsvFilesOfADrumRunLoadWithNumpyAndPandasAsTheyAre) {
    const fs::path run = dir_ / "drum";
    const auto drum = run_command(
        tumble("drum -q --no-plot --grains 300 --omega 8 --revolutions 0.3 --samples 20 --snapshots 20 --out " +
               quoted(run)));
    ASSERT_EQ(drum.exit_code, 0) << drum.output;
    const auto analyze = run_command(tumble("analyze " + quoted(run) + " --first-revolution 0"));
    ASSERT_EQ(analyze.exit_code, 0) << analyze.output;
    const auto r = python(csv_check, quoted(run));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    expect_all_loaded(r.output, {"time_series.csv", "drum_series.csv", "profiles.csv", "axial_msd.csv",
                                 "depth_mobility.csv", "bed_structure.csv", "flow_profile.csv",
                                 "snapshots/000000.csv"});
    EXPECT_NE(read_file(run / "drum_series.csv").find(",mean_z_material_1,"), std::string::npos);

    // The sweep's tables, of this run as a finished point and a pending one
    // (its cells empty).
    tumble::io::SweepSettings settings;
    settings.speeds = {8.0};
    const auto points = tumble::io::expand_sweep(settings, dir_ / "sweep");  // self, two-component
    fs::create_directories(points[1].directory);
    fs::copy_file(run / "summary.json", points[1].directory / "summary.json");
    std::vector<tumble::io::PointResult> results;
    for (const auto& p : points) results.push_back(tumble::io::read_point_result(p));
    EXPECT_EQ(tumble::io::write_sweep_tables(dir_ / "sweep", results), 1u);  // the pending point
    const auto sweep = python(csv_check, quoted(dir_ / "sweep"));
    ASSERT_EQ(sweep.exit_code, 0) << sweep.output;
    expect_all_loaded(sweep.output, {"sweep.csv", "sweep_summary.csv"});
}

// ---- Snapshots: .vtu and .xyz against the CSV of the same step ------------

// Reads snapshot 1 of a run three ways, the CSV by numpy (every double
// exact), the .vtu by VTK's reader, the .xyz as text, and prints whether
// every value agrees exactly.
const char* snapshot_check = R"(
import shlex, sys
import numpy as np
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
from vtkmodules.util.numpy_support import vtk_to_numpy

base = sys.argv[1]
c = np.atleast_1d(np.genfromtxt(base + ".csv", delimiter=",", names=True, dtype=None, encoding="utf-8"))

reader = vtkXMLUnstructuredGridReader()
reader.SetFileName(base + ".vtu")
reader.Update()
grid = reader.GetOutput()
point = lambda name: vtk_to_numpy(grid.GetPointData().GetArray(name))
names_array = grid.GetFieldData().GetAbstractArray("material_names")
names = [names_array.GetValue(k) for k in range(names_array.GetNumberOfValues())]
xyz = np.column_stack([c["x"], c["y"], c["z"]])
v = np.column_stack([c["vx"], c["vy"], c["vz"]])
w = np.column_stack([c["wx"], c["wy"], c["wz"]])
print("vtu",
      grid.GetNumberOfPoints() == len(c),
      np.array_equal(vtk_to_numpy(grid.GetPoints().GetData()), xyz),
      np.array_equal(point("velocity"), v), np.array_equal(point("angular_velocity"), w),
      np.array_equal(point("radius"), c["radius"]), np.array_equal(point("id"), c["id"]),
      [names[m] for m in point("material")] == list(c["material"]),
      vtk_to_numpy(grid.GetFieldData().GetArray("TimeValue"))[0] == c["time"][0])

with open(base + ".xyz") as f:
    count = int(f.readline())
    info = dict(item.split("=", 1) for item in shlex.split(f.readline()))
    rows = [line.split() for line in f]
columns = info["Properties"].split(":")
number = lambda k: np.array([float(r[k]) for r in rows])
print("xyz", count == len(c) == len(rows),
      columns == ["species", "S", "1", "pos", "R", "3", "radius", "R", "1", "id", "I", "1", "velo", "R", "3",
                  "omega", "R", "3", "tag", "I", "1", "kinematic", "I", "1"],
      float(info["Time"]) == c["time"][0], int(info["step"]) == c["step"][0], info["pbc"] == "F F F",
      [r[0] for r in rows] == list(c["material"]),
      np.array_equal(np.column_stack([number(1), number(2), number(3)]), xyz),
      np.array_equal(number(4), c["radius"]), np.array_equal(number(5), c["id"]),
      np.array_equal(np.column_stack([number(6), number(7), number(8)]), v),
      np.array_equal(np.column_stack([number(9), number(10), number(11)]), w))
)";

TEST_F(Formats, VtuAndXyzSnapshotsHoldExactlyWhatTheCsvOfTheSameStepHolds) {
    // Two materials (names with '-'), so that the name table matters.
    std::string scenario = tumble::test_support::walled_box_scenario(
        "0.002", "", "[output]\ndirectory = \"out\"\nsnapshot_interval = 0.001\n");
    std::string second = tumble::test_support::material_m_toml;
    for (const auto& [from, to] : {std::pair{"name = \"m\"", "name = \"grain-b\""},
                                   std::pair{"materials = [\"m\", \"m\"]", "materials = [\"m\", \"grain-b\"]"}})
        second.replace(second.find(from), std::string(from).size(), to);
    scenario += second + "[[pair]]\nmaterials = [\"grain-b\", \"grain-b\"]\nmu = 0.1\nW = 0.2\n" +
                "[[particles]]\nkind = \"random_fill\"\nmaterial = \"grain-b\"\nlo = [-0.015, -0.015, 0.005]\n"
                "hi = [0.015, 0.015, 0.035]\ncount = 5\n";
    const fs::path file = write("s.toml", scenario);
    const auto run = run_command(tumble("run -q " + quoted(file) + " --out " + quoted(dir_ / "run")));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const auto r = python(snapshot_check, quoted(dir_ / "run" / "snapshots" / "000001"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output, "vtu True True True True True True True True\n"
                        "xyz True True True True True True True True True True True\n");
    // The compressed binary file is smaller than the CSV of the same particles.
    EXPECT_LT(fs::file_size(dir_ / "run" / "snapshots" / "000001.vtu"),
              fs::file_size(dir_ / "run" / "snapshots" / "000001.csv"));
}

}  // namespace
