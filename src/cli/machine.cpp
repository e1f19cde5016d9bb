// SPDX-License-Identifier: MIT
#include "cli/machine.hpp"

#include <fstream>
#include <thread>

#include <fmt/format.h>

namespace tumble::cli {

std::string machine_description() {
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string line, model = "unknown CPU";
    while (std::getline(cpuinfo, line))
        if (line.rfind("model name", 0) == 0) {
            model = line.substr(line.find(':') + 2);
            break;
        }
    return fmt::format("{}, {} logical cores", model, std::thread::hardware_concurrency());
}

}  // namespace tumble::cli
