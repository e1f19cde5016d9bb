#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Every interval docs/RESULTS.md quotes, "X [LO, HI]", and every one of
docs/BANDS.md's section "The radial core's baseline", is one the studies
wrote: in a table generated from the runs (studies/*/*.md, written by the
studies' scripts: verdicts.py, comparisons.py, core_baseline.py, ...), or, for the one-seed
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


def section(text, heading):
    """The text under the level-2 heading `heading`, to the next level-2 heading."""
    start = text.index(f"\n## {heading}\n")
    end = text.find("\n## ", start + 1)
    return text[start:] if end < 0 else text[start:end]


def main():
    root = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent)
    tables = "\n".join(p.read_text() for p in sorted(root.glob("studies/*/*.md")))
    known = set(INTERVAL.findall(tables)) | kept_intervals(root)
    status = 0
    for name, text in reports(root):
        quoted = INTERVAL.findall(text)
        missing = sorted({q for q in quoted if q not in known}, key=quoted.index)
        for q in missing:
            print(f"{name}: {q}: in no table of studies/ (nor a kept summary)")
        if not quoted:
            print(f"{name}: no interval quoted")
        if missing or not quoted:
            status = 1
        else:
            print(f"{name}: all {len(quoted)} intervals are the studies' own")
    return status


def reports(root):
    """(name, text) of what is checked: docs/RESULTS.md, and of docs/BANDS.md
    the section on the radial core's baseline (studies/bands/core_baseline.md).
    The file names in single quotes: scripts/check_doc_refs.py reads a name
    and a double-quoted string after it as a reference to a section."""
    results = root / "docs" / 'RESULTS.md'
    bands = root / "docs" / 'BANDS.md'
    heading = "The radial core's baseline"
    return [(str(results.relative_to(root)), results.read_text()),
            (f"{bands.relative_to(root)}, section {heading}", section(bands.read_text(), heading))]


if __name__ == "__main__":
    sys.exit(main())
