// SPDX-License-Identifier: MIT
#include "tumble/core/mpi.hpp"

#include <cstdlib>
#include <string>

#include "tumble/core/error.hpp"

#ifdef TUMBLE_HAVE_MPI
#include <mpi.h>
#endif

namespace tumble::mpi {

namespace {
int world_rank = 0, world_size = 1, world_node_size = 1;

const char* process_environment(const char* name) { return std::getenv(name); }

// The size of the world the launcher announced, or 0 if it said none.
int announced_size(const std::function<const char*(const char*)>& getenv) {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
        if (const char* v = getenv(name); v && *v) return std::atoi(v);
    return 0;
}
}  // namespace

bool launched_by_mpi(const std::function<const char*(const char*)>& getenv) {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
        if (const char* v = getenv(name); v && *v) return true;
    return false;
}

bool launched_by_mpi() {
    return launched_by_mpi(process_environment);
}

bool is_launcher_variable(std::string_view name) {
    for (std::string_view prefix : {"OMPI_", "PMIX_", "PMI_", "MPI_LOCALNRANKS"})
        if (name.substr(0, prefix.size()) == prefix) return true;
    return false;
}

int rank() { return world_rank; }
int size() { return world_size; }
int node_size() { return world_node_size; }
std::string line_prefix() {
    return world_size > 1 ? "[rank " + std::to_string(world_rank) + "/" + std::to_string(world_size) + "] " : "";
}

#ifdef TUMBLE_HAVE_MPI

bool built_with_mpi() { return true; }

Session::Session(int& argc, char**& argv) {
    if (!launched_by_mpi()) return;
    // OpenMPI's shared-memory transport sends a message above its eager
    // limit (4 kB) by a rendezvous and a copy by the kernel: a ghost update
    // of the long drum on 2 ranks (18.6 kB each way) took 22 to 26 us a step
    // (median), 13 to 17 us with the limit at 64 kB (studies/performance/LOG.md,
    // "MPI"). Raised unless the user set it (mpirun --mca sets the same
    // variables); other MPI libraries ignore them.
    setenv("OMPI_MCA_btl_vader_eager_limit", "65536", 0);
    setenv("OMPI_MCA_btl_vader_max_send_size", "65536", 0);
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    active_ = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &world_size);
    MPI_Comm node;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, world_rank, MPI_INFO_NULL, &node);
    MPI_Comm_size(node, &world_node_size);
    MPI_Comm_free(&node);
    const int announced = announced_size(process_environment);
    if (world_size == 1 && announced > 1) {
        MPI_Finalize();
        active_ = false;
        throw Error("the launcher announced " + std::to_string(announced) +
                    " ranks but MPI started this process alone: the launcher and tumble's MPI library do not "
                    "match (Slurm: srun --mpi=pmix, or mpirun from the MPI tumble was built with)");
    }
}

Session::~Session() {
    if (active_) MPI_Finalize();
}

void abort_others(int code) {
    if (world_size > 1) MPI_Abort(MPI_COMM_WORLD, code);
}

void send(int to, int tag, std::string_view text) {
    if (world_size == 1) throw Error("MPI: no other rank to send to");
    MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, to, tag, MPI_COMM_WORLD);
}

namespace {
Message receive_probed(const MPI_Status& status) {
    int count = 0;
    MPI_Get_count(&status, MPI_CHAR, &count);
    Message m{status.MPI_SOURCE, status.MPI_TAG, std::string(static_cast<std::size_t>(count), '\0')};
    MPI_Recv(m.text.data(), count, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return m;
}
}  // namespace

Message receive(int from, int tag) {
    if (world_size == 1) throw Error("MPI: no other rank to receive from");
    MPI_Status status;
    MPI_Probe(from == any_rank ? MPI_ANY_SOURCE : from, tag, MPI_COMM_WORLD, &status);
    return receive_probed(status);
}

std::optional<Message> poll() {
    if (world_size == 1) return std::nullopt;
    int arrived = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status);
    if (!arrived) return std::nullopt;
    return receive_probed(status);
}

Bytes exchange(int to, const Bytes& out, int from, int tag) {
    if (world_size == 1) return out;
    to = to == no_rank ? MPI_PROC_NULL : to;
    from = from == no_rank ? MPI_PROC_NULL : from;
    int outgoing = static_cast<int>(out.size()), incoming = 0;
    MPI_Sendrecv(&outgoing, 1, MPI_INT, to, tag, &incoming, 1, MPI_INT, from, tag, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
    Bytes in(static_cast<std::size_t>(incoming));
    MPI_Sendrecv(out.data(), outgoing, MPI_CHAR, to, tag, in.data(), incoming, MPI_CHAR, from, tag, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
    return in;
}

std::array<Bytes, 2> exchange_pair(const std::array<int, 2>& to, const std::array<Bytes, 2>& out,
                                   const std::array<int, 2>& from, const std::array<std::size_t, 2>& in_size,
                                   const std::array<int, 2>& tag) {
    if (world_size == 1) return out;
    std::array<Bytes, 2> in;
    std::array<MPI_Request, 4> requests{};
    for (std::size_t k = 0; k < 2; ++k) {
        in[k].resize(in_size[k]);
        MPI_Irecv(in[k].data(), static_cast<int>(in_size[k]), MPI_CHAR, from[k] == no_rank ? MPI_PROC_NULL : from[k],
                  tag[k], MPI_COMM_WORLD, &requests[k]);
    }
    for (std::size_t k = 0; k < 2; ++k)
        MPI_Isend(out[k].data(), static_cast<int>(out[k].size()), MPI_CHAR, to[k] == no_rank ? MPI_PROC_NULL : to[k],
                  tag[k], MPI_COMM_WORLD, &requests[2 + k]);
    std::array<MPI_Status, 4> status{};
    MPI_Waitall(4, requests.data(), status.data());
    for (std::size_t k = 0; k < 2; ++k) {
        int count = 0;
        MPI_Get_count(&status[k], MPI_CHAR, &count);
        in[k].resize(from[k] == no_rank ? 0 : static_cast<std::size_t>(count));
    }
    return in;
}

std::vector<Bytes> gather(const Bytes& mine) {
    if (world_size == 1) return {mine};
    int count = static_cast<int>(mine.size());
    std::vector<int> counts(static_cast<std::size_t>(world_size)), offsets(counts.size());
    MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    Bytes all;
    if (world_rank == 0) {
        for (std::size_t r = 1; r < counts.size(); ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
        all.resize(static_cast<std::size_t>(offsets.back() + counts.back()));
    }
    MPI_Gatherv(mine.data(), count, MPI_CHAR, all.data(), counts.data(), offsets.data(), MPI_CHAR, 0,
                MPI_COMM_WORLD);
    std::vector<Bytes> parts;
    if (world_rank == 0)
        for (std::size_t r = 0; r < counts.size(); ++r)
            parts.emplace_back(all.begin() + offsets[r], all.begin() + offsets[r] + counts[r]);
    return parts;
}

std::vector<Bytes> all_gather(const Bytes& mine) {
    if (world_size == 1) return {mine};
    int count = static_cast<int>(mine.size());
    std::vector<int> counts(static_cast<std::size_t>(world_size)), offsets(counts.size());
    MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    for (std::size_t r = 1; r < counts.size(); ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
    Bytes all(static_cast<std::size_t>(offsets.back() + counts.back()));
    MPI_Allgatherv(mine.data(), count, MPI_CHAR, all.data(), counts.data(), offsets.data(), MPI_CHAR, MPI_COMM_WORLD);
    std::vector<Bytes> parts;
    for (std::size_t r = 0; r < counts.size(); ++r)
        parts.emplace_back(all.begin() + offsets[r], all.begin() + offsets[r] + counts[r]);
    return parts;
}

bool any(bool mine) {
    int v = mine ? 1 : 0, all = 0;
    if (world_size == 1) return mine;
    MPI_Allreduce(&v, &all, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
    return all != 0;
}

double sum(double mine) {
    double all = mine;
    if (world_size > 1) MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    return all;
}

std::int64_t sum(std::int64_t mine) {
    std::int64_t all = mine;
    if (world_size > 1) MPI_Allreduce(&mine, &all, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
    return all;
}

double max(double mine) {
    double all = mine;
    if (world_size > 1) MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return all;
}

void sum(std::vector<double>& mine) {
    if (world_size > 1)
        MPI_Allreduce(MPI_IN_PLACE, mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
}

#else  // built without MPI

bool built_with_mpi() { return false; }

Session::Session(int&, char**&) {
    const int announced = announced_size(process_environment);
    if (announced > 1)
        throw Error("started by an MPI launcher with " + std::to_string(announced) +
                    " ranks, but this tumble was built without MPI (CMake option TUMBLE_MPI, libopenmpi-dev): "
                    "every rank would run the same work; rebuild with MPI or run tumble without the launcher");
}

Session::~Session() = default;

void abort_others(int) {}
void send(int, int, std::string_view) { throw Error("MPI: tumble was built without MPI"); }
Message receive(int, int) { throw Error("MPI: tumble was built without MPI"); }
std::optional<Message> poll() { return std::nullopt; }
Bytes exchange(int, const Bytes& out, int, int) { return out; }
std::array<Bytes, 2> exchange_pair(const std::array<int, 2>&, const std::array<Bytes, 2>& out,
                                   const std::array<int, 2>&, const std::array<std::size_t, 2>&,
                                   const std::array<int, 2>&) {
    return out;
}
std::vector<Bytes> gather(const Bytes& mine) { return {mine}; }
std::vector<Bytes> all_gather(const Bytes& mine) { return {mine}; }
bool any(bool mine) { return mine; }
double sum(double mine) { return mine; }
std::int64_t sum(std::int64_t mine) { return mine; }
double max(double mine) { return mine; }
void sum(std::vector<double>&) {}

#endif

}  // namespace tumble::mpi
