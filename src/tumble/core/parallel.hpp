// SPDX-License-Identifier: MIT
// The one way the engine runs work on several threads: a team that works
// through a fixed number of chunks, phase after phase, inside one parallel
// region. Which indices a chunk holds depends only on the number of chunks,
// never on how many threads the OpenMP runtime hands out or in which order
// they run, so a result that combines per-chunk partial sums in chunk order
// is the same bitwise on every run with the same chunk count. Built without
// OpenMP (TUMBLE_OPENMP=OFF), or with one chunk, the chunks run one after
// the other, with the same results.
//
// One region for many time steps instead of one per loop, and a barrier of
// our own between the phases (Barrier): by OpenMP's default policy a thread
// that waits for the others spins for milliseconds before it sleeps, and on
// a machine with more runnable processes than cores it then burns the time
// slice the thread it waits for needs (docs/BENCHMARKS.md, "Threads":
// 2 threads 400 times slower than with OMP_WAIT_POLICY=passive on a loaded
// machine). Ours spins briefly, then sleeps.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <utility>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace tumble {

// Threads the machine offers (1 without OpenMP).
inline int hardware_threads() {
#ifdef _OPENMP
    return omp_get_num_procs();
#else
    return 1;
#endif
}

// Whether this build can run chunks at the same time.
inline constexpr bool parallel_build() {
#ifdef _OPENMP
    return true;
#else
    return false;
#endif
}

// Chunk c of `chunks` equal parts of [0, total): [begin, end).
struct IndexRange {
    std::size_t begin = 0, end = 0;
};
inline IndexRange chunk_range(int c, int chunks, std::size_t total) {
    const auto n = static_cast<std::size_t>(chunks), k = static_cast<std::size_t>(c);
    return {total * k / n, total * (k + 1) / n};
}

// The threads of a team wait here for each other. A waiting thread spins
// for tens of microseconds (the usual imbalance of a phase on an idle
// machine, where waking a sleeping thread would cost as much), then sleeps
// in the kernel (std::atomic::wait, a futex on Linux) until the last one
// arrives, so that it leaves its core to whoever needs it.
class Barrier {
public:
    explicit Barrier(int threads) : threads_(threads) {}
    void wait() {
        const std::uint32_t generation = generation_.load(std::memory_order_acquire);
        // acq_rel: the last to arrive sees what every other thread wrote
        // before arriving, and publishes it with the new generation.
        if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == threads_) {
            arrived_.store(0, std::memory_order_relaxed);
            generation_.fetch_add(1, std::memory_order_release);
            generation_.notify_all();
            return;
        }
        for (int k = 0; k < spins; ++k) {
            if (generation_.load(std::memory_order_acquire) != generation) return;
#if defined(__x86_64__) || defined(__i386__)
            __builtin_ia32_pause();
#endif
        }
        while (generation_.load(std::memory_order_acquire) == generation)
            generation_.wait(generation, std::memory_order_acquire);
    }

private:
    // x86 pause takes 10 to 140 cycles by model: 15 to 200 us in all.
    static constexpr int spins = 4000;
    const int threads_;
    std::atomic<int> arrived_{0};
    std::atomic<std::uint32_t> generation_{0};
};

// The threads of one run_in_team() call. Every thread runs the same body;
// each(f) is one phase: f(c) for every chunk c, spread over the threads, then
// every thread waits until all chunks are done. Code between phases runs on
// every thread alike: it may compute values of its own from shared data
// that an earlier phase finished, but write shared data only inside each().
// Data that several threads share must live outside the body (a local
// variable of the body is one per thread).
class Team {
public:
    int chunks() const { return chunks_; }
    // Whether this is the team's first thread (the only one of a team of one).
    bool leader() const { return rank_ == 0; }
    // The c-th part of [0, total) (chunk_range()).
    IndexRange range(int c, std::size_t total) const { return chunk_range(c, chunks_, total); }

    template <class F>
    void each(F&& f) {
        if (threads_ == 1) {
            for (int c = 0; c < chunks_; ++c) f(c);
            return;
        }
        // Fewer threads than chunks (OMP_DYNAMIC, a thread limit) is fine:
        // a thread then takes every threads-th chunk.
        for (int c = rank_; c < chunks_; c += threads_) {
            try {
                f(c);
            } catch (...) {
                fail(std::current_exception());
            }
        }
        wait();
    }
    // each(f) without the wait, for a phase after which every chunk goes on
    // with its own data only (the next phase must not read what another
    // chunk writes here): a thread may then start the next phase of its
    // chunks while others finish this one.
    template <class F>
    void each_own(F&& f) {
        for (int c = threads_ == 1 ? 0 : rank_; c < chunks_; c += threads_) {
            try {
                f(c);
            } catch (...) {
                if (threads_ == 1) throw;
                fail(std::current_exception());  // seen at the next wait
            }
        }
    }
    // f() once, on one thread; then all wait.
    template <class F>
    void one(F&& f) {
        each([&](int c) {
            if (c == 0) f();
        });
    }

private:
    // What the threads of a team share: the first failure of a chunk, which
    // every thread sees after the next barrier and leaves the body on, so
    // that none waits at a barrier the others never reach.
    struct Shared {
        explicit Shared(int threads) : barrier(threads) {}
        Barrier barrier;
        std::exception_ptr failure;
        bool failed = false;
    };
    struct Leave {};  // thrown by every thread of a failed team, caught in run_in_team()

    Team(int chunks, int rank, int threads, Shared* shared)
        : chunks_(chunks), rank_(rank), threads_(threads), shared_(shared) {}

    void fail(std::exception_ptr e) {
#ifdef _OPENMP
#pragma omp critical(tumble_team_failure)
#endif
        if (!shared_->failed) {
            shared_->failure = std::move(e);
            shared_->failed = true;
        }
    }
    void wait() {
        shared_->barrier.wait();
        if (shared_->failed) throw Leave{};
    }

    int chunks_ = 1, rank_ = 0, threads_ = 1;
    Shared* shared_ = nullptr;

    template <class F>
    friend void run_in_team(int chunks, F&& body);
};

// body(team) on the threads of one parallel region, `chunks` chunks (one
// thread per chunk when the runtime allows). An exception thrown in a chunk
// ends the body on every thread and is thrown again here.
template <class F>
void run_in_team(int chunks, F&& body) {
#ifdef _OPENMP
    if (chunks > 1) {
        std::unique_ptr<Team::Shared> shared;  // made once the team's size is known
#pragma omp parallel num_threads(chunks)
        {
#pragma omp single
            shared = std::make_unique<Team::Shared>(omp_get_num_threads());
            Team team(chunks, omp_get_thread_num(), omp_get_num_threads(), shared.get());
            try {
                body(team);
            } catch (const Team::Leave&) {
            } catch (...) {  // thrown between phases: alike on every thread
                team.fail(std::current_exception());
            }
        }
        if (shared->failed) std::rethrow_exception(shared->failure);
        return;
    }
#endif
    Team::Shared shared(1);
    Team team(chunks, 0, 1, &shared);
    body(team);
}

}  // namespace tumble
