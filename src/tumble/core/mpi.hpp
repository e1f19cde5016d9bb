// SPDX-License-Identifier: MIT
// MPI, when tumble is built with it (CMake option TUMBLE_MPI, on in
// scripts/build.sh; OpenMPI from Debian's libopenmpi-dev): the world's rank
// and size, and text messages between ranks. Without MPI (or without a
// launcher) the world is one rank, 0 of 1, and sending is an error.
//
// MPI is started only when a launcher started the process (mpirun, mpiexec,
// srun: launched_by_mpi()), so that a plain `tumble ...` never pays for it
// and a child process of a rank (a sweep's point) can run MPI of its own.
// Only the thread that started MPI calls it (MPI_THREAD_FUNNELED): the
// OpenMP threads of a time step never do.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tumble::mpi {

// True if this binary was built with MPI.
bool built_with_mpi();

// True if the environment is that of a process started by an MPI launcher
// (OpenMPI's OMPI_COMM_WORLD_SIZE, PMIx's PMIX_RANK, PMI's PMI_RANK or
// PMI_SIZE, as MPICH, Intel MPI and Slurm's srun --mpi set). `getenv` is
// injectable for tests.
bool launched_by_mpi(const std::function<const char*(const char*)>& getenv);
bool launched_by_mpi();

// The names of the launchers' variables above (and OMPI_*, PMIX_*, PMI_*,
// MPI_LOCALNRANKS in general): a child process started by a rank gets an
// environment without them (io/sweep.hpp, spawn_process), so that it does
// not take itself for one of the parent's ranks.
bool is_launcher_variable(std::string_view name);

// MPI for the life of the object: initialised if launched_by_mpi(), else
// nothing (the world is one rank). One per process, made in main(). Throws
// tumble::Error if the launcher asked for more than one rank and this
// binary has no MPI (it would run the same work on every rank).
class Session {
public:
    Session(int& argc, char**& argv);
    ~Session();
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;
    bool active() const { return active_; }

private:
    bool active_ = false;
};

// The world: rank and size (0 and 1 without a Session that started MPI);
// ranks on this node (for a default number of jobs per rank); "[rank R/S] "
// when the world has more than one rank, else empty (the start of a line
// that several ranks may print).
int rank();
int size();
int node_size();
std::string line_prefix();

// Ends every rank of the job with `code`: an error on one rank must not leave
// the others waiting for its messages. Where the world is one rank, does nothing.
void abort_others(int code);

// Messages of text, tagged. `to` and `from` are ranks; any_rank receives
// from whichever rank sent first.
inline constexpr int any_rank = -1;
struct Message {
    int from = 0;
    int tag = 0;
    std::string text;
};
void send(int to, int tag, std::string_view text);
// Blocks until a message of `tag` from `from` (or any_rank) arrives.
Message receive(int from, int tag);
// A message of any tag from any rank if one has arrived, without waiting.
std::optional<Message> poll();

// Bytes between ranks, for one simulation shared among the ranks
// (sim/slabs.hpp). Collective calls: every rank of the world makes them, in
// the same order. With one rank each returns its input (exchange() with
// rank 0 itself included), so the callers need no case of their own.
using Bytes = std::vector<char>;
// Sends `out` to rank `to` and receives what rank `from` sends to this one
// (MPI_Sendrecv: no two ranks wait for each other). A rank of -1 (no_rank)
// is none: nothing is sent, or nothing received.
inline constexpr int no_rank = -1;
Bytes exchange(int to, const Bytes& out, int from, int tag);
// Two such exchanges at once, where the receiver knows each size (the ghost
// updates between rebuilds): out[k] to rank to[k], and at most in_size[k]
// bytes from rank from[k] (what arrived, resized to it), tag tag[k]. All
// four messages are posted together (MPI_Isend, MPI_Irecv, MPI_Waitall), so
// the two directions cost one latency, and no message's size goes first.
std::array<Bytes, 2> exchange_pair(const std::array<int, 2>& to, const std::array<Bytes, 2>& out,
                                   const std::array<int, 2>& from, const std::array<std::size_t, 2>& in_size,
                                   const std::array<int, 2>& tag);
// Every rank's `mine`, in rank order, on rank 0 (empty elsewhere).
std::vector<Bytes> gather(const Bytes& mine);
// The same on every rank.
std::vector<Bytes> all_gather(const Bytes& mine);
// Logical or, sum and maximum over the ranks; the result on every rank.
bool any(bool mine);
double sum(double mine);
std::int64_t sum(std::int64_t mine);
double max(double mine);
void sum(std::vector<double>& mine);  // element by element, in place

}  // namespace tumble::mpi
