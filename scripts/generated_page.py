# SPDX-License-Identifier: MIT
"""A documentation page made by a script, never edited by hand: written
with --write, compared with --check (scripts/cli_reference.py,
scripts/python_reference.py). Standard library only."""
import difflib
import os


def write_or_check(page, made, mode, source, command):
    """Writes `made` to `page` (--write), or exits 1 with the difference and
    `command`, the way to write it again, where the page is not `made`
    (--check). `source`: what the page is made from, for the messages."""
    name = os.path.relpath(page, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    if mode == "--write":
        with open(page, "w", encoding="utf-8") as f:
            f.write(made)
        print(f"wrote {name}")
        return 0
    try:
        with open(page, encoding="utf-8") as f:
            kept = f.read()
    except FileNotFoundError:
        kept = ""
    if kept != made:
        print("".join(difflib.unified_diff(kept.splitlines(True), made.splitlines(True), name, source)))
        print(f"\n{name} differs from {source}; write it again with:\n    {command}")
        return 1
    print(f"{name} is {source}")
    return 0
