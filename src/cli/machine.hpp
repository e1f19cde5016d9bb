// SPDX-License-Identifier: MIT
#pragma once

#include <string>

namespace tumble::cli {

// "CPU model, N logical cores" from /proc/cpuinfo, for benchmark reports.
std::string machine_description();

}  // namespace tumble::cli
