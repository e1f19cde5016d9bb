// SPDX-License-Identifier: MIT
// Checkpoints of a run (docs/CHECKPOINTS.md): the scenario, the complete
// engine state (tumble/sim/simulation_state.hpp) and a record of named values
// in which the command keeps its settings and how far it got, including the
// length of each output file at that moment.
//
// A file RUN/checkpoints/NNNNNN.tck (NNNNNN counts up) is
//   "TUMBLECK"                 8 bytes, the magic
//   format version             uint32 (checkpoint_format_version)
//   payload length             uint64, bytes
//   payload                    the record, the scenario, the state
//   CRC-32 of all of the above uint32
// all little-endian. It is written to NNNNNN.tck.tmp, flushed to the disk
// (fsync), renamed into place and the directory flushed, so a crash while
// writing leaves the previous checkpoint as it was; the newest two are kept.
//
// A run shared among MPI ranks (sim/slabs.hpp) keeps one file per rank,
// RUN/checkpoints/NNNNNN.rR.tck for rank R, each written by its rank with
// that rank's spheres and ghosts (no rank gathers the whole state), the
// scenario in each, and the rank count and its rank in the record ("ranks",
// "rank").
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "tumble/sim/scenario.hpp"
#include "tumble/sim/simulation_state.hpp"

namespace tumble::io {

// 2: slip vector history, friction normal; 3: viscous force history; 4: own
// spheres and slab state of a rank (sim/slabs.hpp); 5: and the slab cuts;
// 6: the model's tangential stiffness (earlier files: the paper's); 7: the
// scenario's smooth walls (earlier files: none); 8: the mesh walls, their
// triangles, and the mesh feature each wall history slot follows (earlier
// files: no meshes); 9: a mesh wall's side, the insertions and how many
// spheres each has poured in (earlier files: none).
// (From 16:51 to 19:20 UTC of 2026-11-30 tumble wrote the cuts under the
// number 4; a file of format 4 is read with the cuts, and if that does not
// fit its bytes, without. A rank's file of format 4 without cuts resumes on
// another number of ranks or on one process, not on as many.)
inline constexpr std::uint32_t checkpoint_format_version = 9;

// Named values; reading a missing key, or one of another kind, throws
// tumble::Error naming the source (the checkpoint file) and the key.
class CheckpointRecord {
public:
    using Value = std::variant<double, std::int64_t, std::string, std::vector<double>>;

    void set(const std::string& key, Value value) { values_[key] = std::move(value); }
    bool has(const std::string& key) const { return values_.count(key) != 0; }
    double number(const std::string& key) const { return get<double>(key, "a number"); }
    std::int64_t integer(const std::string& key) const { return get<std::int64_t>(key, "an integer"); }
    const std::string& text(const std::string& key) const { return get<std::string>(key, "a text"); }
    const std::vector<double>& numbers(const std::string& key) const {
        return get<std::vector<double>>(key, "a list of numbers");
    }
    const std::map<std::string, Value>& values() const { return values_; }
    std::string source;  // for messages: where the record was read from

private:
    template <class T>
    const T& get(const std::string& key, const char* kind) const;

    std::map<std::string, Value> values_;
};

struct Checkpoint {
    CheckpointRecord record;
    Scenario scenario;
    SimulationState state;
};

// The bytes of a checkpoint file, and back. decode_checkpoint checks the
// magic, the version, the length and the checksum before it reads anything,
// and throws tumble::Error "NAME: reason" for a damaged or foreign file.
std::string encode_checkpoint(const Checkpoint& checkpoint);
Checkpoint decode_checkpoint(std::string_view bytes, const std::string& name);

// Whose checkpoint files: rank `rank` of `ranks` (one rank: NNNNNN.tck).
struct CheckpointRank {
    int rank = 0, ranks = 1;
};

// RUN/checkpoints/*.tck of a rank, oldest first.
std::vector<std::filesystem::path> checkpoint_files(const std::filesystem::path& run_directory,
                                                    CheckpointRank who = {});

// Writes the next checkpoint of the run (see above) and removes all but the
// newest two. Returns its path; tumble::Error naming the file on failure
// (disk full, no permission), with no partial file left under a valid name.
// `number`: NNNNNN, by default next_checkpoint_number(); the ranks of a
// shared run agree on one.
std::filesystem::path write_checkpoint(const std::filesystem::path& run_directory, const Checkpoint& checkpoint,
                                       CheckpointRank who = {}, long number = 0);
// One after the highest NNNNNN of any checkpoint file of the run, of one
// process or of ranks: a run that goes on on another number of ranks (or on
// one process) numbers on from where it was, so that the names sort in the
// order of the moments whatever wrote them.
long next_checkpoint_number(const std::filesystem::path& run_directory);

// The newest checkpoint that reads back intact and whose output files are at
// least as long as it recorded; `rejected` gets a message for each newer one
// that did not (damaged, truncated, not a regular file, over max_bytes, its
// output files cut short by a crash). tumble::Error if none.
struct LoadedCheckpoint {
    Checkpoint checkpoint;
    std::filesystem::path file;
    std::vector<std::string> rejected;
};
LoadedCheckpoint load_newest_checkpoint(const std::filesystem::path& run_directory,
                                        std::uintmax_t max_bytes = std::numeric_limits<std::uintmax_t>::max(),
                                        CheckpointRank who = {});

// The checkpoint of rank `who` of a run shared among as many ranks: the
// newest number of which every rank holds an intact file (a rank whose newer
// file is damaged takes the ranks back with it; each such file is in
// `rejected`). Collective: every rank calls it, before any other exchange;
// the ranks then compare their files' steps, times, rank counts, ranks and
// runs (command and scenario), and every rank throws the same tumble::Error,
// naming the files and what differs, if they do not belong together or a
// rank has no intact file.
LoadedCheckpoint load_shared_checkpoint(const std::filesystem::path& run_directory, std::uintmax_t max_bytes,
                                        CheckpointRank who);

// The newest checkpoint of a run shared among ranks as one whole state
// (tumble/sim/simulation.hpp, whole_state()): rank 0's newest intact file,
// then the files of the other ranks of that moment, merged; its record is
// rank 0's, with "ranks" 1. For a resume on another number of ranks (every
// rank reading every file: the whole state in memory meanwhile).
// tumble::Error if a file is missing or damaged, or not of rank 0's moment
// and run.
LoadedCheckpoint load_whole_checkpoint(const std::filesystem::path& run_directory,
                                       std::uintmax_t max_bytes = std::numeric_limits<std::uintmax_t>::max());

// The kind of files that holds the run's newest moment: {} (one process,
// NNNNNN.tck) or {0, 2} (ranks, NNNNNN.rR.tck: rank 0's). A run that went on
// on one process after ranks, or on ranks after one process, has both; the
// later step wins (a kind none of whose files reads back loses).
CheckpointRank newest_checkpoint_kind(const std::filesystem::path& run_directory,
                                      std::uintmax_t max_bytes = std::numeric_limits<std::uintmax_t>::max());

// True if the run stopped before its end and has an intact checkpoint to go
// on from (its record's "finished" is 0).
bool resumable(const std::filesystem::path& run_directory,
               std::uintmax_t max_bytes = std::numeric_limits<std::uintmax_t>::max());

// Output files: flush each (that exists) to the disk and keep its length under
// "file:NAME", and cut each file back to its recorded length when resuming, so that what the
// interrupted run wrote after the checkpoint is written again, identically.
// The files are series written a whole row at a time: a checkpoint whose
// length of one ends inside a row, or whose snapshot times are not in order
// up to its state's time, is passed over as damaged (load_newest_checkpoint).
void record_file_lengths(CheckpointRecord& record, const std::filesystem::path& directory,
                         std::initializer_list<const char*> names);
void truncate_to_recorded_lengths(const CheckpointRecord& record, const std::filesystem::path& directory);

}  // namespace tumble::io
