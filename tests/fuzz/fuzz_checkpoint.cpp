// SPDX-License-Identifier: MIT
// libFuzzer target: the checkpoint decoder on arbitrary bytes. Most inputs
// fail the checksum; with -use_value_profile and seeds from real
// checkpoints libFuzzer also gets past it. Any outcome but a checkpoint or a
// tumble::Error is a bug. Run by scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "io/checkpoint.hpp"
#include "tumble/core/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        tumble::io::decode_checkpoint(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.tck");
    } catch (const tumble::Error&) {
    }
    return 0;
}
