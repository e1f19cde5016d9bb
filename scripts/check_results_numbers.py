#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Every interval docs/RESULTS.md quotes, "X [LO, HI]", is one the studies
wrote: in a table generated from the runs (studies/*/*.md, written by the
studies' scripts: verdicts.py, comparisons.py, ...), or, for the one-seed
shear-model runs of 12 revolutions, the D and interval of a kept summary
(studies/shear_models/summaries/*_12__*.json, in 1e-5 m^2/rev). A number
typed into the report, or one left behind when a table is generated anew,
fails here, named.

    python3 scripts/check_results_numbers.py [REPOSITORY]

Standard library only.
"""

import json
import re
import sys
from pathlib import Path

NUMBER = r"[-+]?\d+(?:\.\d+)?%?"
INTERVAL = re.compile(rf"{NUMBER} \[{NUMBER}, {NUMBER}\]")


def kept_intervals(root):
    """The D [lo, hi] of every component and estimator of the 12-revolution shear-model runs."""
    out = set()
    for path in (root / "studies" / "shear_models" / "summaries").glob("*_12__*.json"):
        for c in json.loads(path.read_text())["components"]:
            for e in (c["msd"], c["hogg_free"]):
                out.add(f"{e['D'] * 1e5:.2f} [{e['D_lo'] * 1e5:.2f}, {e['D_hi'] * 1e5:.2f}]")
    return out


def main():
    root = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent)
    report = (root / "docs" / 'RESULTS.md').read_text()
    tables = "\n".join(p.read_text() for p in sorted(root.glob("studies/*/*.md")))
    known = set(INTERVAL.findall(tables)) | kept_intervals(root)
    quoted = INTERVAL.findall(report)
    missing = sorted({q for q in quoted if q not in known}, key=quoted.index)
    for q in missing:
        print(f"docs/RESULTS.md: {q}: in no table of studies/ (nor a kept summary)")
    if missing or not quoted:
        return 1
    print(f"docs/RESULTS.md: all {len(quoted)} intervals are the studies' own")
    return 0


if __name__ == "__main__":
    sys.exit(main())
