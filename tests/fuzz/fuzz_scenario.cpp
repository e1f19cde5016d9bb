// SPDX-License-Identifier: MIT
// libFuzzer target: the scenario reader (TOML) on arbitrary bytes. Any
// outcome but a scenario or a tumble::Error (a crash, a hang, another
// exception, memory beyond the limit) is a bug. Run by scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "io/config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        tumble::io::parse_run_config(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.toml", ".");
    } catch (const tumble::Error&) {
    }
    return 0;
}
