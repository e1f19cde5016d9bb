// SPDX-License-Identifier: MIT
#include "tumble/core/isa.hpp"

#include <atomic>
#include <cstdlib>

#if defined(__x86_64__)
#include <cpuid.h>
#endif

#include "tumble/core/error.hpp"

namespace tumble {

namespace {

constexpr Isa all_levels[] = {Isa::baseline, Isa::avx2, Isa::avx512, Isa::avx512_wide};

// What each level needs of the processor: GCC's names of the x86-64 levels
// (including the operating system's support of the wider registers).
bool processor_runs(Isa level) {
#if TUMBLE_ISA_CHOICE
    __builtin_cpu_init();
    switch (level) {
        case Isa::baseline: return true;
        case Isa::avx2: return __builtin_cpu_supports("x86-64-v3");
        case Isa::avx512:
        case Isa::avx512_wide: return __builtin_cpu_supports("x86-64-v4");
    }
    return false;
#else
    return level == Isa::baseline;
#endif
}

std::string level_list(const std::vector<Isa>& levels) {
    std::string text;
    for (Isa level : levels) text += (text.empty() ? "" : ", ") + std::string(isa_name(level));
    return text;
}

Isa chosen_by_environment() {
    const char* value = std::getenv("TUMBLE_ISA");
    const std::vector<Isa> available = available_isas();
    if (value == nullptr || *value == '\0') return default_isa(available, processor_has_full_width_512());
    if constexpr (!TUMBLE_ISA_CHOICE)
        throw Error(std::string("TUMBLE_ISA=") + value + ": this tumble has no choice of instruction set: " +
                    isa_description() + "; the default build has one (TUMBLE_ARCH empty, GCC, x86-64)");
    for (Isa level : all_levels)
        if (isa_name(level) == value) {
            if (!processor_runs(level))
                throw Error(std::string("TUMBLE_ISA=") + value + ": this processor lacks its instructions; it runs " +
                            level_list(available));
            return level;
        }
    throw Error(std::string("TUMBLE_ISA=") + value +
                ": unknown; one of baseline, avx2, avx512, avx512-wide (this processor runs " + level_list(available) +
                ")");
}

// The level in use, or -1 before the first call of isa_in_use().
std::atomic<int> level_in_use{-1};

}  // namespace

std::string_view isa_name(Isa level) {
    switch (level) {
        case Isa::baseline: return "baseline";
        case Isa::avx2: return "avx2";
        case Isa::avx512: return "avx512";
        case Isa::avx512_wide: return "avx512-wide";
    }
    return "?";
}

Isa default_isa(const std::vector<Isa>& available, bool full_width_512) {
    if (available.back() == Isa::avx512_wide && !full_width_512) return Isa::avx512;
    return available.back();
}

bool processor_has_full_width_512() {
#if defined(__x86_64__)
    unsigned a = 0, b = 0, c = 0, d = 0;
    if (!__get_cpuid(0, &a, &b, &c, &d)) return false;
    const bool amd = b == 0x68747541 && d == 0x69746e65 && c == 0x444d4163;  // "AuthenticAMD"
    if (!amd || !__get_cpuid(1, &a, &b, &c, &d)) return false;
    // The family: the base field, plus the extended field when the base is 0Fh.
    const unsigned base = (a >> 8) & 0xf;
    const unsigned family = base == 0xf ? base + ((a >> 20) & 0xff) : base;
    return family >= 0x1a;
#else
    return false;
#endif
}

std::vector<Isa> available_isas() {
    std::vector<Isa> levels;
    for (Isa level : all_levels)
        if (processor_runs(level)) levels.push_back(level);
    return levels;
}

Isa isa_in_use() {
    int level = level_in_use.load(std::memory_order_relaxed);
    if (level < 0) {
        level = static_cast<int>(chosen_by_environment());
        level_in_use.store(level, std::memory_order_relaxed);
    }
    return static_cast<Isa>(level);
}

void use_isa(Isa level) {
    if (!processor_runs(level))
        throw Error(std::string("instruction set ") + std::string(isa_name(level)) +
                    ": not available; this tumble on this processor runs " + level_list(available_isas()));
    level_in_use.store(static_cast<int>(level), std::memory_order_relaxed);
}

std::string isa_description() {
#if TUMBLE_ISA_CHOICE
    constexpr const char* x86_level[] = {"x86-64", "x86-64-v3", "x86-64-v4, 256-bit vectors",
                                         "x86-64-v4, 512-bit vectors"};
    const Isa level = isa_in_use();
    return std::string(isa_name(level)) + " (" + x86_level[static_cast<int>(level)] + "; this processor runs " +
           level_list(available_isas()) + ")";
#elif defined(TUMBLE_MARCH)
    return std::string("-march=") + TUMBLE_MARCH + " (TUMBLE_ARCH, fixed when built)";
#else
    return "the compiler's default for this architecture (fixed when built)";
#endif
}

}  // namespace tumble
