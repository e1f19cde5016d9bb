#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A drum run directory read into pandas and numpy, and analysed again with
tumble's own estimators (the Hogg fit, the grains' axial MSD).

    PYTHONPATH=build/python python3 examples/python/read_run.py DIR
"""

import sys

import tumble

run = tumble.io.Run(sys.argv[1] if len(sys.argv) > 1 else "drum-out")
series = run.drum_series
print(f"{len(series)} samples over {series['revolutions'].iloc[-1]:.2f} revolutions; columns: {list(series.columns)}")
print(f"{len(run.snapshot_files)} snapshots; the last:")
print(run.snapshot(-1).describe().loc[["mean", "std"], ["x", "y", "z", "vx", "vy", "vz"]])
for k, component in enumerate(run.components):
    N, z = run.mean_z(k)
    hogg = run.fit_hogg(k, first_revolution=0.0)
    # The run's own D (summary.txt's headline): the same estimator and lag window.
    msd = run.msd(k)
    if msd["determined"]:
        msd_text = f"MSD D = {msd['D']:.3g} m^2/rev, 95 % [{msd['D_lo']:.3g}, {msd['D_hi']:.3g}]"
    else:
        msd_text = f"MSD D not determined: {msd['note']}"
    print(f"{component['name']}: <z> from {z[0] * 1e3:+.2f} to {z[-1] * 1e3:+.2f} mm; "
          f"Hogg D = {hogg['D']:.3g} m^2/rev ({'determined' if hogg['determined'] else hogg['note']}); {msd_text}")
summary = run.summary
print("summary.json keys:", ", ".join(sorted(summary)))
