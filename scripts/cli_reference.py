#!/usr/bin/env python3
"""The command-line reference, docs/reference/cli.md, made from the
program's own help: `tumble --help` and `tumble COMMAND --help` for every
command it lists. The page is generated, never edited by hand, so it
cannot drift from the program: the ctest `cli_reference` fails when the
help and the page differ, and says how to write the page again.

    python3 scripts/cli_reference.py build/tumble --write   # write the page
    python3 scripts/cli_reference.py build/tumble --check   # exit 1 if it differs

Standard library only.
"""
import os
import re
import subprocess
import sys

from generated_page import write_or_check

PAGE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "reference", "cli.md")


def help_text(binary, *args):
    """The help of `tumble ARGS --help`, with the program's path written as `tumble`."""
    out = subprocess.run([binary, *args, "--help"], capture_output=True, text=True, check=True,
                         env={**os.environ, "COLUMNS": "80"}).stdout
    return out.replace(binary, "tumble").rstrip() + "\n"


def environment_note(text):
    """Splits the environment note, the same at the end of every help, from a help text."""
    m = re.search(r"\n\nEnvironment: .*\Z", text, re.S)
    return (text[:m.start()] + "\n", m.group(0).strip()) if m else (text, "")


def page(binary):
    top, env = environment_note(help_text(binary))
    commands = re.findall(r"^  (\w[\w-]*)\s{2,}", top.split("Subcommands:", 1)[1], re.M) if "Subcommands:" in top else []
    parts = [
        "# Command line: `tumble` and its commands",
        "",
        "This page is made from the program's own help "
        "(`python3 scripts/cli_reference.py build/tumble --write`); the test "
        "`cli_reference` fails when the two differ. The same text is printed by "
        "`tumble --help` and `tumble COMMAND --help`.",
        "",
        "```text",
        top.rstrip(),
        "```",
        "",
    ]
    if env:
        parts += [env, ""]
    for command in commands:
        text, _ = environment_note(help_text(binary, command))
        parts += [f"## `tumble {command}`", "", "```text", text.rstrip(), "```", ""]
    return "\n".join(parts)


def main():
    if len(sys.argv) != 3 or sys.argv[2] not in ("--write", "--check"):
        sys.exit(__doc__)
    binary, mode = sys.argv[1], sys.argv[2]
    sys.exit(write_or_check(PAGE, page(binary), mode, "the program's help",
                            "python3 scripts/cli_reference.py build/tumble --write"))


if __name__ == "__main__":
    main()
