// SPDX-License-Identifier: MIT
// The scenario reader: a TOML file (format: docs/SCENARIO.md) -> RunConfig.
//
// Every key is checked before anything runs: unknown keys, missing keys,
// wrong types, impossible values, unknown names, an incomplete pair table,
// starting positions outside the domain, periodic axes too short for the
// neighbour search, tumble::scenario_problem(), overlapping initial
// particles (and flat walls), motions too fast, and the time step.
// Any failure throws ConfigError with the message
//
//     FILE: KEY: REASON
//
// KEY is the path of the offending value, written as follows:
//   - a key in a table:            simulation.duration, domain.lo
//   - an entry of an array of
//     tables ([[material]] etc.):  material[1].nu   (0-based, in file order)
//   - an element of an array:      domain.lo[2], pair[0].materials[1]
//   - nested arrays of tables:     particles[2].particles[5].position
//   - a whole table or block:      material[1], particles[0]
//   - a CSV cell:                  line 7, column vx   (FILE is then the CSV)
//   - a TOML syntax error:         line 3, column 12
// Indices count from 0, as the entries appear in the file. Where the value
// exists in the file, REASON ends with its line number, "(line 23)".
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "tumble/core/error.hpp"
#include "tumble/sim/scenario.hpp"

namespace tumble::io {

// The most spheres a scenario may hold, all blocks and CSV files together: a
// guard against typos such as counts = [1000, 1000, 1000] and against
// running out of memory before anything is checked (10^7 spheres take about
// 1 GB while the scenario is read). The same limit as tumble drum's grains.
inline constexpr std::size_t max_scenario_particles = 10'000'000;

struct OutputSettings {
    // Where a run writes; relative paths are relative to the working
    // directory of the run (not to the scenario file).
    std::filesystem::path directory = "tumble-out";
    // s between two rows of time_series.csv. 0: no periodic rows, only the
    // final state. The reader's default when the key is absent is
    // duration / 100 (101 rows).
    double time_series_interval = 0.0;
    // s between two snapshots; 0: none.
    double snapshot_interval = 0.0;
};

// The keys of the coarse-grained fields taken during a run: the scenario's
// [fields], tumble run --fields KEY=VALUE (experiments::parse_fields_during_run;
// docs/FIELDS.md, "During a run").
inline constexpr std::string_view field_keys[] = {"every", "from",   "samples", "lo",     "hi",    "cell", "cells",
                                                  "average", "kernel", "width", "format", "frame", "span"};

struct RunConfig {
    Scenario scenario;
    double duration = 0.0;  // s of simulated time
    std::uint64_t seed = 1;
    OutputSettings output;
    // [fields] as KEY=VALUE items (numbers written to round-trip, arrays as
    // X,Y,Z), checked when the run plans them; none: no fields during the run.
    std::vector<std::string> fields;
    std::filesystem::path source;  // the scenario file (or the name given to parse_run_config)
};

// Bad input. what() is "FILE: KEY: REASON" ("FILE: REASON" when no key
// applies); the three parts are also available on their own.
class ConfigError : public tumble::Error {
public:
    ConfigError(const std::filesystem::path& file, std::string key, std::string reason);
    const std::filesystem::path& file() const { return file_; }
    const std::string& key() const { return key_; }
    const std::string& reason() const { return reason_; }

private:
    std::filesystem::path file_;
    std::string key_;
    std::string reason_;
};

// The spheres a scenario's [[particles]] blocks will make, counted from
// their keys before any is made: a lattice's counts, a random fill's count
// and radii; a list's entries and a CSV file's rows (read by then: an input
// file's size bounds them).
struct ParticleCount {
    std::size_t spheres = 0;
    double smallest_radius = 0.0, largest_radius = 0.0;  // m
    // The keys that set the count: "particles[0].counts"; with several
    // blocks the three largest with their counts
    // ("particles[0].counts 900000, particles[2].count 1000, and 2 more blocks").
    std::string keys;
};
// Called by the reader once every key is read and checked and the spheres
// are counted, before any particle is made, with the settings (`particles`
// still empty) and the count; it refuses by throwing (the memory a run will
// need: experiments::scenario_memory_check).
using ParticleCheck = std::function<void(const RunConfig& settings, const ParticleCount& count)>;

// Reads and checks a scenario file. CSV files it names are found relative to
// the file's directory.
RunConfig load_run_config(const std::filesystem::path& file, const ParticleCheck& check = {});

// The same from text: `name` is used in messages (and as RunConfig::source),
// `base_dir` resolves relative CSV paths.
RunConfig parse_run_config(std::string_view toml_text, const std::filesystem::path& name,
                           const std::filesystem::path& base_dir, const ParticleCheck& check = {});

}  // namespace tumble::io
