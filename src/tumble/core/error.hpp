// SPDX-License-Identifier: MIT
// The engine reports impossible input or impossible physics by throwing
// tumble::Error; the CLI turns it into a message and a non-zero exit.
#pragma once

#include <stdexcept>
#include <string>

namespace tumble {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace tumble
