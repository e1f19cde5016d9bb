// SPDX-License-Identifier: MIT
// The 27 periodic image shifts of a box, coded 0..26. A pair stores the code
// of the image of j that is near i: d = X_i - X_j + shift(code).
#pragma once

#include <array>
#include <cstdint>

#include "tumble/core/domain.hpp"
#include "tumble/core/vec3.hpp"

namespace tumble {

inline constexpr std::uint8_t no_shift = 13;  // (0, 0, 0)

// code = (sx + 1) + 3 (sy + 1) + 9 (sz + 1), shift = (sx Lx, sy Ly, sz Lz).
inline constexpr std::uint8_t image_code(int sx, int sy, int sz) {
    return static_cast<std::uint8_t>((sx + 1) + 3 * (sy + 1) + 9 * (sz + 1));
}

class PeriodicImages {
public:
    PeriodicImages() = default;
    explicit PeriodicImages(const Domain& domain) : periodic_(domain.periodic[0] || domain.periodic[1] || domain.periodic[2]) {
        const Vec3 L = domain.length();
        for (int sz = -1; sz <= 1; ++sz)
            for (int sy = -1; sy <= 1; ++sy)
                for (int sx = -1; sx <= 1; ++sx)
                    shift_[image_code(sx, sy, sz)] = {sx * L.x, sy * L.y, sz * L.z};
    }
    const Vec3& operator[](std::uint8_t code) const { return shift_[code]; }
    // Whether the domain has a periodic axis; if not, every pair's code is
    // no_shift, and the pair loop leaves the shift out.
    bool periodic() const { return periodic_; }

private:
    std::array<Vec3, 27> shift_{};
    bool periodic_ = false;
};

}  // namespace tumble
