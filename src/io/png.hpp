// SPDX-License-Identifier: MIT
// PNG files of a render::Image (8-bit RGB), through libpng's simplified API.
#pragma once

#include <filesystem>

#include "io/render/raster.hpp"

namespace tumble::io {

// Writes the image; `fast` trades file size for speed (frames that are read
// once by ffmpeg). tumble::Error naming the file and libpng's reason on failure.
void write_png(const std::filesystem::path& file, const render::Image& image, bool fast = false);

// Reads any PNG as 8-bit RGB (alpha is composed onto black); tumble::Error
// naming the file and the reason on failure.
render::Image read_png(const std::filesystem::path& file);

}  // namespace tumble::io
