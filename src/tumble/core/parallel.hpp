// SPDX-License-Identifier: MIT
// The one way the engine runs work on several threads: a loop over a fixed
// number of chunks of an index range. Which indices a chunk holds depends
// only on the number of chunks, never on how many threads the OpenMP runtime
// hands out or in which order they run, so a result that combines per-chunk
// partial sums in chunk order is the same bitwise on every run with the same
// chunk count. Built without OpenMP (TUMBLE_OPENMP=OFF) the chunks run one
// after the other, with the same results.
#pragma once

#include <cstddef>

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

// f(c) for c = 0 .. chunks-1, one chunk per thread (chunks threads).
template <class F>
void for_each_chunk(int chunks, F&& f) {
#ifdef _OPENMP
    if (chunks > 1) {
#pragma omp parallel for num_threads(chunks) schedule(static, 1)
        for (int c = 0; c < chunks; ++c) f(c);
        return;
    }
#endif
    for (int c = 0; c < chunks; ++c) f(c);
}

// f(i) for every i in [0, total), split into `chunks` chunks.
template <class F>
void parallel_for(int chunks, std::size_t total, F&& f) {
    for_each_chunk(chunks, [&](int c) {
        const IndexRange r = chunk_range(c, chunks, total);
        for (std::size_t i = r.begin; i < r.end; ++i) f(i);
    });
}

}  // namespace tumble
