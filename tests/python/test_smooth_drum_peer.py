# SPDX-License-Identifier: MIT
"""The analysis of the smooth drum's comparison with LAMMPS
(bench/peers/smooth_drum_peer.py: the angle of repose and the flowing
layer's depth, measured alike from both codes' snapshots), checked on
synthetic beds whose answers are known."""

import math
import os
import pathlib
import sys

import pytest

SOURCE = pathlib.Path(os.environ.get("TUMBLE_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
sys.path.insert(0, str(SOURCE / "bench" / "peers"))
import smooth_drum_peer  # noqa: E402

REACH = 0.037  # m: where grain centres can be in the 4 cm drum


def tilted_bed(angle_deg, surface, base, shear_rate=20.0, spacing=4e-4, radius=1e-3):
    """Grains on a square grid in the cross-section (one z), filling the circle
    of radius REACH below a surface at s = r . n = surface (n the upward normal
    of a surface inclined angle_deg, raised toward +x). Each moves down the
    slope at u = shear_rate (s - base): down above base, up below it."""
    a = math.radians(angle_deg)
    tx, ty = math.cos(a), math.sin(a)
    nx, ny = -ty, tx
    grains = []
    n = int(REACH / spacing) + 1
    for i in range(-n, n + 1):
        for j in range(-n, n + 1):
            x, y = i * spacing, j * spacing
            s = x * nx + y * ny
            if x * x + y * y > REACH * REACH or s > surface:
                continue
            u = shear_rate * (s - base)
            grains.append((x, y, 0.0, -u * tx, -u * ty, 0.0, radius))
    return grains


@pytest.mark.parametrize("angle", [-10.0, 0.0, 26.0, 38.0])
def test_the_angle_is_the_surface_inclination_of_a_circular_segment(angle):
    # the principal axis of a circular segment is parallel to its chord
    measured, _, _ = smooth_drum_peer.angle_of_repose(tilted_bed(angle, -0.016, -0.027))
    assert measured == pytest.approx(angle, abs=0.2)


def test_the_layer_ends_where_the_downhill_velocity_changes_sign():
    bed = tilted_bed(26.0, -0.016, -0.027)
    depth, s_f, s_0, u_f, half = smooth_drum_peer.flowing_layer([(1.0, bed), (1.1, bed)])
    assert s_f == pytest.approx(-0.016, abs=6e-4)   # half a bin, and the grid's step
    assert s_0 == pytest.approx(-0.027, abs=1e-4)   # linear in s: exact but for the bins' means
    assert depth == pytest.approx(0.011, abs=7e-4)
    # the top bin's mean velocity, of grains up to one bin below the surface
    assert u_f == pytest.approx(20.0 * (s_f + 0.027), abs=20.0 * smooth_drum_peer.BIN)
    assert half == pytest.approx(0.5 * (s_f - s_0), abs=6e-4)


def test_a_bed_without_a_sign_change_is_refused():
    bed = tilted_bed(26.0, -0.016, -0.040)  # everything flows down
    with pytest.raises(SystemExit):
        smooth_drum_peer.flowing_layer([(1.0, bed)])
