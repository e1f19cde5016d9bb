#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A scenario built as a Python dict and stepped from Python: 150 grains of
the paper's material 1 poured into a box with flat walls, run until they
have nearly come to rest; then the particles and contacts as numpy arrays.

    PYTHONPATH=build/python python3 examples/python/scenario_steps.py
"""

import numpy as np

import tumble

material_1 = dict(name="material-1", E=1.0e6, G=0.3e6, nu=0.25, xi=500.0, eta=500.0, rho=1000.0, radius=0.0036)
scenario = tumble.Scenario.from_dict({
    "simulation": {"duration": 1.0, "seed": 3, "gravity": [0.0, 0.0, -9.81]},
    "domain": {"lo": [-0.03, -0.03, 0.0], "hi": [0.03, 0.03, 0.08], "walls": [True, True, True],
               "wall_material": "material-1"},
    "material": [material_1],
    "pair": [{"materials": ["material-1", "material-1"], "mu": 0.1, "W": 0.2}],
    "particles": [{"kind": "random_fill", "material": "material-1", "count": 150,
                   "lo": [-0.025, -0.025, 0.005], "hi": [0.025, 0.025, 0.075]}],
})
sim = tumble.Simulation(scenario)
print(f"{sim.size} grains, dt = {sim.dt:.3g} s")


def nearly_at_rest(s):
    """True when the rms grain speed is below 2 cm/s (after 0.1 s of fall)."""
    return s.time > 0.1 and np.sqrt(np.mean(np.sum(s.velocities**2, axis=1))) < 0.02


steps = sim.run(duration=scenario.duration, until=nearly_at_rest, check_every=500)
print(f"stopped after {steps} steps, t = {sim.time:.3f} s")

# The arrays are in the engine's order, which changes at re-sorts: use the ids.
z = sim.positions[sim.by_id, 2]
print(f"bed height: highest grain centre {z.max() * 100:.2f} cm, mean {z.mean() * 100:.2f} cm")
contacts = sim.contacts()
print(f"{len(contacts['id_i'])} contacts; largest overlap {contacts['overlap'].max() * 1e6:.1f} um, "
      f"mean normal force {contacts['normal_force'].mean() * 1e3:.3f} mN, "
      f"largest slip {np.linalg.norm(contacts['slip'], axis=1).max() * 1e6:.2f} um")
print("energies:", sim.observe()["kinetic_translational"], "J")
