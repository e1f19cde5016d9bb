#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The drum experiment of `tumble drum` run from Python, with a callback at
every sample: here a small self-diffusion drum (a few grains, a fraction of a
revolution, so that it takes seconds); the paper's drum is
tumble.run_drum(out="drum-out") with the defaults.

    PYTHONPATH=build/python python3 examples/python/drum_callback.py [OUT]
"""

import sys

import numpy as np

import tumble

out = sys.argv[1] if len(sys.argv) > 1 else "drum-python"
history = []


def on_sample(sample):
    """Keeps <z> of each half and prints the fastest grain."""
    history.append([sample.revolutions] + [c.mean_z for c in sample.components])
    p = sample.particles
    free = p["motions"] < 0
    speed = np.linalg.norm(p["velocities"][free], axis=1)
    print(f"N = {sample.revolutions:.3f}: <z> left {sample.components[0].mean_z * 1e3:+.2f} mm, "
          f"right {sample.components[1].mean_z * 1e3:+.2f} mm; fastest grain {p['ids'][free][speed.argmax()]} "
          f"at {speed.max():.3f} m/s")


directory = tumble.run_drum(mode="self", grains=6, length=0.03, diameter=0.03, omega=20.0, revolutions=0.4,
                            samples=10, snapshots=10, out=out, force=True, on_sample=on_sample)
history = np.array(history)
print(f"{len(history)} samples; the run is in {directory}")
