#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""docs/reference/outputs.md names every file tumble writes and every column
and key in it, and nothing else. This runs tumble on small cases (a drum, a
scenario with a wall and its fields, a deeper drum and its fields in the
drum's frame, a sweep of two points, the benchmark's JSON), reads what they wrote (CSV headers, JSON and TOML keys, the data
arrays of the VTK files, the columns of the extended XYZ files) and fails,
naming them, on

- a file with no section on the page, and a file of the list of what a run
  directory holds (run_files in src/io/output.hpp) with none;
- a column or key with no entry in its file's section;
- an entry that none of the runs wrote.

The page's form: a section per file, its heading the file's path in
backticks (NNNNNN: a number, NAME and POINT: any name); a table whose first
cell holds the entries, each in backticks. In an entry, <x> stands for a
name (a material, a component, a wall, an index) and {S} for every entry of
the section headed `{S}` (or of the file `S`), so a JSON object written in
several places is described once. A JSON key a[] is a list; a[].b a key of
its objects. A key whose value is null or an empty list in these runs
covers the entries below it, which the runs cannot show.

    python3 scripts/check_outputs.py build/tumble [REPOSITORY]

Standard library only; about 20 s (the sweep's figures take most of it).
"""

import json
import os
import re
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

NAME = "[A-Za-z0-9_-]+"
BENCH = "tumble bench --json"


def sections(page):
    """{heading token: [entries]} of the page: each backticked token of the
    ## and ### headings, and the backticked names in the first cell of the
    rows of the tables below it."""
    out, current = {}, []
    for line in page.splitlines():
        if re.match(r"#{2,3} ", line):
            current = re.findall(r"`([^`]+)`", line)
            out.update({name: [] for name in current})
        elif line.startswith("| `"):
            cell = line.split("|")[1]
            for name in current:
                out[name] += [n.strip() for token in re.findall(r"`([^`]+)`", cell) for n in token.split(",")]
    return out


def expand(entry, shapes, seen=()):
    """An entry with each {S} replaced by the entries of section S."""
    m = re.search(r"\{([^}]+)\}", entry)
    if not m:
        return [entry]
    if m.group(1) in seen or m.group(1) not in shapes:
        raise SystemExit(f"docs/reference/outputs.md: {entry}: no section `{{{m.group(1)}}}` or `{m.group(1)}`")
    head, tail = entry[:m.start()], entry[m.end():]
    return [x for sub in shapes[m.group(1)] for x in expand(head + sub + tail, shapes, seen + (m.group(1),))]


def pattern(entry):
    return re.compile(re.sub(r"<[^>]+>", NAME, re.escape(entry).replace(r"\<", "<").replace(r"\>", ">")))


def prefixes(entry):
    """The entry cut before each '.' and '[]': the keys that hold it."""
    return [entry[:i] for i in range(len(entry)) if entry[i] == "." or entry.startswith("[]", i)]


def json_keys(value, path=""):
    """{key: opaque} of a JSON or TOML value; opaque: null or an empty container."""
    if isinstance(value, dict) and value:
        return {k: o for key, v in value.items() for k, o in json_keys(v, f"{path}.{key}" if path else key).items()}
    if isinstance(value, list) and value and all(isinstance(x, dict) for x in value):
        return {k: o for x in value for k, o in json_keys(x, path + "[]").items()}
    if isinstance(value, list):
        return {path + "[]": not value}
    return {path: value is None or value == {}}


def file_keys(path):
    """{column or key: opaque} of a file tumble wrote; None for a file whose
    contents the page does not list (images, checkpoints, indexes, text)."""
    name = path.name
    if name.endswith(".csv"):
        return dict.fromkeys(path.read_text().splitlines()[0].split(","), False)
    if name.endswith(".json"):
        return json_keys(json.loads(path.read_text()))
    if name == "drum_run.toml":
        return json_keys(tomllib.loads(path.read_text()))
    if name.endswith((".vtu", ".vtp", ".vti")):
        head = path.read_bytes().split(b"<AppendedData", 1)[0].decode()
        return dict.fromkeys(re.findall(r'<DataArray [^>]*Name="([^"]+)"', head), False)
    if name.endswith(".xyz"):
        line = path.read_text().splitlines()[1]
        properties = re.search(r"Properties=(\S+)", line).group(1).split(":")[::3]
        return dict.fromkeys(re.findall(r"(\w+)=", line) + properties, False)
    return None


def run(tumble, work, root):
    """Runs the cases into work; returns {path relative to its directory: file} and the bench's JSON."""
    data = root / "tests" / "data" / "outputs"
    quiet = dict(check=True, stdout=subprocess.DEVNULL, cwd=work)
    # A two-component drum long enough for every file of its analysis: the
    # grains' MSD after N = 1, the start's boundary between its halves
    # (band_edges.csv: 24 bins), the band watch (until_band_change).
    subprocess.run([tumble, "drum", "-q", "--grains", "40", "--length", "0.06", "--diameter", "0.03", "--omega", "20",
                    "--revolutions", "2.5", "--snapshots", "10", "--band-bins", "24", "--until-band-change", "2",
                    "--no-plot", "--out", "drum"], **quiet)
    subprocess.run([tumble, "analyze", "drum", "--so-far"], **quiet)
    subprocess.run([tumble, "run", str(data / "scenario.toml"), "--out", "run", "-q"], **quiet)
    subprocess.run([tumble, "fields", "run", "-q"], **quiet)
    # A drum deep enough for a free surface, and its fields in the drum's frame.
    subprocess.run([tumble, "drum", "-q", "--grains", "600", "--revolutions", "0.3", "--no-plot", "--out", "frame"],
                   **quiet)
    subprocess.run([tumble, "fields", "frame", "--frame", "drum", "--frame-cells", "2,2", "--samples", "3", "-q"],
                   **quiet)
    subprocess.run([tumble, "sweep", str(data / "sweep.toml"), "--out", "sweep", "-q"], **quiet)
    bench = subprocess.run([tumble, "bench", "--size", "4", "--steps", "10", "--warmup", "2", "--json"],
                           capture_output=True, text=True, check=True).stdout
    files = {}
    for top in ("drum", "frame", "run", "sweep"):
        for path in sorted((work / top).rglob("*")):
            if path.is_file() and path.name != ".tumble.lock":
                files[f"{top}: {path.relative_to(work / top)}"] = path
    return files, json_keys(json.loads(bench))


def section_of(relative, names):
    """The section whose heading names this file; a sweep point's files and
    those of so_far/ as a drum run's."""
    inner = re.sub(r"^(points/[^/]+|so_far)/", "", relative)
    for candidate in dict.fromkeys((relative, inner)):
        for name in names:
            regex = re.sub(r"NAME|POINT", "[^/]+", re.escape(name).replace("NNNNNN", r"\d+"))
            if re.fullmatch(regex, candidate):
                return name
    return None


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    tumble = os.path.abspath(sys.argv[1])
    root = Path(sys.argv[2] if len(sys.argv) == 3 else Path(__file__).resolve().parent.parent)
    page = sections((root / "docs" / "reference" / "outputs.md").read_text())
    shapes = {name.strip("{}"): entries for name, entries in page.items()}
    files = [name for name in page if name != BENCH and not name.startswith("{")]
    problems = []

    listed = re.search(r"run_files\[\] = \{(.*?)\};", (root / "src/io/output.hpp").read_text(), re.S).group(1)
    for name in re.findall(r'"([^"]+)"', listed):
        if not any(f == name or f.startswith(name + "/") for f in files):
            problems.append(f"{name} (run_files, src/io/output.hpp): no section")

    with tempfile.TemporaryDirectory() as work:
        written, bench = run(tumble, Path(work), root)
        seen = {name: {} for name in page}
        seen[BENCH] = bench
        for label, path in written.items():
            name = section_of(label.split(": ", 1)[1], files)
            if name is None:
                problems.append(f"{label}: no section")
                continue
            keys = file_keys(path)
            for key, opaque in (keys or {}).items():  # opaque only where every file has it so
                seen[name][key] = seen[name].get(key, True) and opaque

    for name in files + [BENCH]:
        if not page[name]:
            continue
        entries = [e for entry in page[name] for e in expand(entry, shapes)]
        regexes = [(e, pattern(e), [pattern(p) for p in prefixes(e)]) for e in entries]
        keys = seen[name]
        if not keys:
            problems.append(f"{name}: has entries but none of the runs wrote it")
            continue
        opaque = [k for k, o in keys.items() if o]
        for key, is_opaque in keys.items():
            if not any(r.fullmatch(key) or (is_opaque and any(p.fullmatch(key) for p in ps)) for _, r, ps in regexes):
                problems.append(f"{name}: {key}: no entry")
        for entry, r, ps in regexes:
            if not any(r.fullmatch(k) for k in keys) and not any(p.fullmatch(k) for p in ps for k in opaque):
                problems.append(f"{name}: the entry {entry}: not written")

    for line in problems:
        print(f"docs/reference/outputs.md: {line}")
    if problems:
        return 1
    print(f"docs/reference/outputs.md has an entry for every column and key of {len(written)} files, and no other")
    return 0


if __name__ == "__main__":
    sys.exit(main())
