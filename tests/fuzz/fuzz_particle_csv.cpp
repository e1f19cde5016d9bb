// SPDX-License-Identifier: MIT
// libFuzzer target: the particle CSV reader on arbitrary bytes (written to
// a file, as the reader reads files). Any outcome but particles or a
// tumble::Error is a bug. Run by scripts/fuzz.sh.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/particle_csv.hpp"
#include "tumble/core/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::filesystem::path file =
        std::filesystem::temp_directory_path() / ("tumble-fuzz-" + std::to_string(::getpid()) + ".csv");
    std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                 static_cast<std::streamsize>(size));
    static const std::vector<tumble::Material> materials{
        {"m", 1e6, 0.3e6, 0.25, 500.0, 500.0, 1000.0, 3.6e-3}, {"wall", 1e6, 0.3e6, 0.25, 500.0, 500.0, 1000.0, 3e-3}};
    try {
        tumble::io::read_particle_csv(file, materials, {"drum"});
    } catch (const tumble::Error&) {
    }
    return 0;
}
