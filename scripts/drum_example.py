#!/usr/bin/env python3
"""The worked example of docs/DRUM.md ("A worked example: the default run"):
the output of the README's main job, `build/tumble drum --out drum-out
--force` (scripts/run.sh), between the lines

    <!-- drum-example: begin -->  and  <!-- drum-example: end -->

It runs that command (in a scratch directory, with `--progress-every 0`: a
progress line says how fast this machine is, not what the run found) and

    python3 scripts/drum_example.py --check [--tumble PROGRAM]    fails when the block differs
    python3 scripts/drum_example.py --update [--tumble PROGRAM]   writes the block anew

What depends on the machine, not on the run, is left out of the comparison:
the instruction set the hot loops ran (every level gives the same results
bit for bit), and the wall time, speed and time by phase of the rotation. Everything else,
the time step, the settling, every number of the analysis, must match to
the digit (one thread: a fixed thread count gives the same bits). The
ctest test drum_example (label long) runs --check. Standard library only.
"""
import argparse
import difflib
import os
import re
import subprocess
import sys
import tempfile

SOURCE = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
DOC = os.path.join(SOURCE, 'docs', 'DRUM.md')
BEGIN, END = "<!-- drum-example: begin -->", "<!-- drum-example: end -->"
COMMAND = ["drum", "--out", "drum-out", "--force", "--progress-every", "0"]

# (pattern, replacement): the parts of a line that depend on the machine.
MACHINE = [
    (re.compile(r"instruction set \S+ \([^)]*\)"), "instruction set <this processor's>"),
    (re.compile(r"rotation simulated in \S+ s: \S+ grain updates/s \(\S+ s per revolution\)"),
     "rotation simulated in <s>: <grain updates/s> (<s per revolution>)"),
    (re.compile(r"^(time by phase of the rotation \([^)]*\)): \S+ s, "), r"\1: <s>, "),
    (re.compile(r"^(  [a-z ]+?)\s+\d+\.\d+ s\s+\d+\.\d+ %$"), r"\1 <s> <%>"),
]


def machine_free(lines):
    out = []
    for line in lines:
        for pattern, replacement in MACHINE:
            line = pattern.sub(replacement, line)
        out.append(line)
    return out


def run_example(tumble):
    """The command's output, as the docs show it."""
    with tempfile.TemporaryDirectory(prefix="tumble-drum-example-") as scratch:
        result = subprocess.run([tumble] + COMMAND, cwd=scratch, capture_output=True, text=True)
        if result.returncode != 0:
            sys.stderr.write(result.stdout + result.stderr)
            sys.exit(f"drum_example: `tumble {' '.join(COMMAND)}` failed with exit code {result.returncode}")
        return result.stdout.rstrip("\n").split("\n")


def read_doc():
    with open(DOC, encoding="utf-8") as f:
        text = f.read()
    if text.count(BEGIN) != 1 or text.count(END) != 1:
        sys.exit(f"drum_example: {DOC} needs one {BEGIN} and one {END}")
    head, rest = text.split(BEGIN)
    block, tail = rest.split(END)
    body = block.strip("\n").split("\n")
    if len(body) < 2 or not body[0].startswith("```") or body[-1] != "```":
        sys.exit(f"drum_example: the block between the markers of {DOC} is not one fenced code block")
    return head, body[1:-1], tail


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    what = parser.add_mutually_exclusive_group(required=True)
    what.add_argument("--check", action="store_true", help="fail when the documented block differs")
    what.add_argument("--update", action="store_true", help="write the block anew")
    parser.add_argument("--tumble", default=os.path.join(SOURCE, "build", "tumble"), help="the tumble program")
    args = parser.parse_args()
    head, documented, tail = read_doc()
    lines = run_example(os.path.abspath(args.tumble))
    if args.update:
        with open(DOC, "w", encoding="utf-8") as f:
            f.write(head + BEGIN + "\n```\n" + "\n".join(lines) + "\n```\n" + END + tail)
        print(f"drum_example: {DOC} updated ({len(lines)} lines)")
        return 0
    want, got = machine_free(documented), machine_free(lines)
    if want == got:
        print(f"drum_example: {DOC} matches the run ({len(lines)} lines)")
        return 0
    sys.stdout.writelines(difflib.unified_diff([l + "\n" for l in want], [l + "\n" for l in got],
                                               "docs/DRUM.md", "tumble " + " ".join(COMMAND)))
    print("drum_example: docs/DRUM.md's worked example differs from the run; "
          "regenerate it: python3 scripts/drum_example.py --update")
    return 1


if __name__ == "__main__":
    sys.exit(main())
