#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Every key that tumble's readers accept has an entry in the reference:
the scenario file's in docs/SCENARIO.md (as `key`, or as a quoted value
for the kinds), the drum file's in docs/DRUM.md's table (as `[section] key`).
The keys are the lists the readers check a table against (only_keys in
src/io/config.cpp and src/io/drum_config.cpp), so a key added to a reader
without its line in the reference fails here.

    python3 scripts/check_doc_keys.py [REPOSITORY]
"""

import re
import sys
from pathlib import Path

LIST = re.compile(r'\{\s*("[a-z_0-9]+"(?:\s*,\s*"[a-z_0-9]+")*)\s*\}')
WORD = re.compile(r'"([a-z_0-9]+)"')


def scenario_keys(source):
    """Every word in a brace list of quoted words in the scenario reader."""
    return {w for found in LIST.findall(source) for w in WORD.findall(found)}


def drum_keys(source):
    """(section, key) of every only_keys(*t, "section", {...}) in the drum reader."""
    calls = re.findall(r'only_keys\(\s*\*\s*\w+\s*,\s*"([a-z_]+)"\s*,\s*\{([^}]*)\}', source)
    return {(section, key) for section, keys in calls for key in WORD.findall(keys)}


def main():
    root = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent)
    missing = []
    docs = root / "docs"
    scenario = docs.joinpath('SCENARIO.md').read_text()
    for key in sorted(scenario_keys((root / "src/io/config.cpp").read_text())):
        forms = (f"`{key}`", f'"{key}"', f"{key} =", f"`[{key}]`", f"`[[{key}]]`")  # a key, a kind, a table
        if not any(form in scenario for form in forms):
            missing.append(f"docs/SCENARIO.md: no entry for the scenario key {key}")
    drum = docs.joinpath('DRUM.md').read_text()
    for section, key in sorted(drum_keys((root / "src/io/drum_config.cpp").read_text())):
        entry = f"`[{section}] {key}`"
        if section == "materials":  # one row names the four roles
            entry = "`[materials] large`, `small`, `wall`, `cap`"
        if entry not in drum:
            missing.append(f"docs/DRUM.md: no row {entry} in the drum file's table")
    for line in missing:
        print(line)
    if missing:
        return 1
    print("every key of the scenario and drum files has its entry")
    return 0


if __name__ == "__main__":
    sys.exit(main())
