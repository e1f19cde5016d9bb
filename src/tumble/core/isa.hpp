// SPDX-License-Identifier: MIT
// Instruction sets: one binary that runs on every x86-64 processor and uses
// the vector width of the one it runs on.
//
// The default build (CMake TUMBLE_ARCH empty) compiles everything for the
// baseline x86-64 (SSE2), so that a binary made on one machine runs on any
// other, and compiles the hot loops (the pair loop, the kicks and the drift,
// the adding up of the threads' forces) four times from the same source:
// for the baseline, for x86-64-v3 (AVX2) and twice for x86-64-v4 (AVX-512),
// with 4 and with 8 doubles per instruction. The level is chosen once per
// process: the widest the processor has (8 doubles only where the
// processor runs them at full rate, default_isa() below), or the one named
// by the environment variable TUMBLE_ISA (baseline, avx2, avx512,
// avx512-wide), to compare them or to rule one out.
//
// How: run_for_isa(f) calls f through one of four copies of a one-line
// function template that differ only in their `target` attribute; `flatten`
// inlines into each copy all that f calls, so f's loops are compiled (and
// vectorised) for that copy's instructions. What is not inlined (here only
// the memory allocation of the recorded contacts' list) stays a baseline
// function, so no code for a wider instruction set can be reached on a
// processor without it. The choice is a switch on a value read once, not
// GCC's `target_clones`, whose resolver picks the version before main() and
// cannot be told to use a lower level. Compiling a translation unit several
// times with different -march would not be safe: the inline functions and
// templates it shares with the rest of the program would exist in several
// versions under one name, and the linker would keep any one of them.
//
// Every level gives the same results bitwise: the build contracts no
// multiply-add (-ffp-contract=off) and vector square roots and divisions
// round as the scalar ones (docs/BENCHMARKS.md "Portable binary").
//
// A build for one processor (TUMBLE_ARCH=native or any -march value), a
// compiler other than GCC (clang, for the fuzzers) or another architecture
// (aarch64) has one level: the build's own flags.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(TUMBLE_MARCH)
#define TUMBLE_ISA_CHOICE 1
#else
#define TUMBLE_ISA_CHOICE 0
#endif

namespace tumble {

// The levels, narrowest first. In a build without the choice only
// `baseline` exists, and it means the build's flags. avx512 and
// avx512_wide run the same instructions, on 256-bit and on 512-bit vectors.
enum class Isa { baseline, avx2, avx512, avx512_wide };

// "baseline", "avx2", "avx512", "avx512-wide": the names TUMBLE_ISA takes.
std::string_view isa_name(Isa level);

// The levels this binary has code for and this processor can run,
// narrowest first.
std::vector<Isa> available_isas();

// The level a processor gets without TUMBLE_ISA, from the levels it runs
// (narrowest first): the widest, except that avx512-wide is kept for
// processors that execute 512-bit vectors at full rate (`full_width_512`),
// others get avx512. Measured (docs/BENCHMARKS.md, "Vector width by
// processor"): on an AMD Zen 5 8 doubles per instruction ran the long drum
// 9 % and the cube 15 % faster than 4; on an Intel Xeon (family 6 model
// 167) 9 % slower.
Isa default_isa(const std::vector<Isa>& available, bool full_width_512);

// Whether this processor executes 512-bit vector instructions in one pass:
// AMD's family 1Ah (Zen 5) and later. (Zen 4 splits them into two 256-bit
// halves; Intel's processors lower their clock; neither was measured faster.)
bool processor_has_full_width_512();

// The level the hot loops run on: on the first call, TUMBLE_ISA if it is
// set, else default_isa() of this processor. tumble::Error if TUMBLE_ISA names an
// unknown level or one this binary or processor lacks. Simulation's
// constructor calls it, so the error comes before any thread starts.
Isa isa_in_use();

// Runs the hot loops on `level` from now on (tests and benchmarks);
// tumble::Error if it is not available.
void use_isa(Isa level);

// The level in use for reports: "avx2 (x86-64-v3; this processor runs
// baseline, avx2, avx512, avx512-wide)", or "-march=native (TUMBLE_ARCH, fixed when
// built)".
std::string isa_description();

namespace isa_detail {

// f() with all it calls inlined, compiled for one level.
template <class F>
[[gnu::flatten]] void run_baseline(F& f) {
    f();
}
#if TUMBLE_ISA_CHOICE
template <class F>
[[gnu::flatten, gnu::target("arch=x86-64-v3")]] void run_avx2(F& f) {
    f();
}
// 4 doubles per instruction, as GCC's tuning for Intel's processors with
// AVX-512 chooses: with 8 the cube and the long drum ran 9 % slower on an
// Intel Xeon (docs/BENCHMARKS.md).
template <class F>
[[gnu::flatten, gnu::target("arch=x86-64-v4,prefer-vector-width=256")]] void run_avx512(F& f) {
    f();
}
// 8 doubles per instruction: 9 to 15 % faster than 4 on an AMD Zen 5.
template <class F>
[[gnu::flatten, gnu::target("arch=x86-64-v4,prefer-vector-width=512")]] void run_avx512_wide(F& f) {
    f();
}
#endif

}  // namespace isa_detail

// f(), compiled for the level in use. For a loop, not for a step: the
// choice is made at each call.
template <class F>
void run_for_isa(F&& f) {
#if TUMBLE_ISA_CHOICE
    switch (isa_in_use()) {
        case Isa::avx512_wide: return isa_detail::run_avx512_wide(f);
        case Isa::avx512: return isa_detail::run_avx512(f);
        case Isa::avx2: return isa_detail::run_avx2(f);
        case Isa::baseline: break;
    }
#endif
    isa_detail::run_baseline(f);
}

}  // namespace tumble
