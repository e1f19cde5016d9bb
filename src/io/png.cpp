// SPDX-License-Identifier: MIT
#include "io/png.hpp"

#include <png.h>

#include <string>

#include "io/output.hpp"
#include "tumble/core/error.hpp"

namespace tumble::io {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& file, const std::string& action, png_image& png) {
    const std::string reason = png.message;
    png_image_free(&png);
    throw Error(file.string() + ": cannot " + action + " PNG: " + reason);
}

}  // namespace

void write_png(const fs::path& file, const render::Image& image, bool fast) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(image.width());
    png.height = static_cast<png_uint_32>(image.height());
    png.format = PNG_FORMAT_RGB;
    if (fast) png.flags |= PNG_IMAGE_FLAG_FAST;
    // Encoded in memory, then written whole (write_file_whole): a failed
    // write or a kill leaves no cut image under the file's name.
    png_alloc_size_t size = 0;
    if (!png_image_write_get_memory_size(png, size, 0, image.data(), 0, nullptr)) fail(file, "write", png);
    std::string bytes(size, '\0');
    if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, image.data(), 0, nullptr)) fail(file, "write", png);
    bytes.resize(size);
    write_file_whole(file, bytes);
}

render::Image read_png(const fs::path& file) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&png, file.c_str())) fail(file, "read", png);
    png.format = PNG_FORMAT_RGB;
    render::Image image(static_cast<int>(png.width), static_cast<int>(png.height));
    if (!png_image_finish_read(&png, nullptr, image.data(), 0, nullptr)) fail(file, "read", png);
    return image;
}

}  // namespace tumble::io
