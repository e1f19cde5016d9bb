// SPDX-License-Identifier: MIT
#include "experiments/machine.hpp"

#include <fstream>
#include <thread>

#include <fmt/format.h>

#include "tumble/core/error.hpp"
#include "tumble/core/parallel.hpp"

namespace tumble::experiments {

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

int resolve_threads(int requested) {
    const int threads = requested > 0 ? requested : hardware_threads();
    if (threads > 1 && !parallel_build()) {
        fmt::print(stderr, "tumble: note: built without OpenMP (TUMBLE_OPENMP=OFF); running on 1 thread\n");
        return 1;
    }
    if (threads > hardware_threads())
        throw Error(fmt::format("--threads: {} is more than the {} logical cores of this machine (threads beyond "
                                "the cores only wait for each other; 0 uses them all)",
                                threads, hardware_threads()));
    return threads;
}

std::string thread_binding() {
#ifdef _OPENMP
    switch (omp_get_proc_bind()) {
        case omp_proc_bind_true: return "true";
        case omp_proc_bind_master: return "master";
        case omp_proc_bind_close: return "close";
        case omp_proc_bind_spread: return "spread";
        default: break;
    }
#endif
    return "none";
}

}  // namespace tumble::experiments
