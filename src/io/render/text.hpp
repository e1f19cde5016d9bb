// SPDX-License-Identifier: MIT
// Text on a frame of `tumble render` (the legend and the clock): a 5 x 7
// pixel font of printable ASCII, drawn without anti-aliasing, each font
// pixel a square of `scale` image pixels. Characters outside printable ASCII
// are drawn as '?'.
#pragma once

#include <string_view>

#include "io/render/raster.hpp"

namespace tumble::io::render {

// Pixels of one line of text: its height, and the advance per character
// (the glyph and one column of space).
constexpr int text_height(int scale) { return 7 * scale; }
constexpr int text_advance(int scale) { return 6 * scale; }
int text_width(std::string_view text, int scale);

// Draws `text` with its top left corner at pixel (x, y); what falls outside
// the image is left out.
void draw_text(Image& image, int x, int y, std::string_view text, Rgb colour, int scale);

}  // namespace tumble::io::render
