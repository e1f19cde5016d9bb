#!/usr/bin/env python3
"""Every reference to a section of one of the project's Markdown files
(`docs/BENCHMARKS.md, "Portable binary"`, `ARCHITECTURE.md ("Threads")`)
names a heading that file has: the quoted words stand in one of its
headings (case aside; a reference may shorten a long heading). Reads the
files git tracks; prints each reference that names no heading and exits 1
if there is one. Standard library only.

    python3 scripts/check_doc_refs.py [REPO]
"""
import os
import re
import subprocess
import sys

repo = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
os.chdir(repo)
try:  # the files git tracks; outside a checkout, every file but the builds'
    tracked = subprocess.run(["git", "ls-files"], capture_output=True, text=True, check=True).stdout.split()
except (OSError, subprocess.CalledProcessError):
    tracked = [os.path.relpath(os.path.join(d, f)) for d, dirs, files in os.walk(".") for f in files
               if not d.startswith(("./build", "./.git", "./studies/bands/out"))]
# A bare name is a file at the top or in docs/; a path names its own.
markdown = {os.path.basename(f): f for f in tracked if f.endswith(".md") and os.path.dirname(f) in ("", "docs")}
markdown.update({f: f for f in tracked if f.endswith(".md")})


def headings(path):
    """The headings of a Markdown file, and the bold words that open a
    paragraph or a list item (`**Threads** (core/parallel.hpp) ...`), which
    the docs use as named places too."""
    places = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            if re.match(r"^#{1,4} ", line):
                places.append(re.sub(r"^#+\s*", "", line).strip().lower())
            lead = re.match(r"^\s*(?:[-*] |\d+\. )?\*\*([^*]+)", line)  # to its end or the line's
            if lead:
                places.append(lead.group(1).strip().lower())
    return places


known = {name: headings(path) for name, path in markdown.items()}
# A file name, then at most a comma, parenthesis, colon or escaped quote,
# then the quoted words; a second title may follow after "and" or a comma.
reference = re.compile(r'((?<![\w/.-])(?:[\w.-]+/)*[A-Z][A-Z-]+\.md)[\s,(:\\]{0,4}"([^"\n]{3,200})"((?:\s*(?:and|,)\s*\\?"[^"\n]{3,200}")*)')
comment = re.compile(r"\s*\n\s*(?://|#|\*)?\s*")  # a comment or paragraph running on to the next line
bad = 0
for path in tracked:
    if path.endswith((".png", ".gz", ".tck", ".csv", ".vtu", ".jsonl")):
        continue
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except (UnicodeDecodeError, IsADirectoryError, FileNotFoundError):
        continue
    joined = comment.sub(" ", text)
    for m in reference.finditer(joined):
        name = m.group(1)
        if name not in known:
            continue  # a file outside the project (../shared/SPEC-NOTES.md)
        for title in [m.group(2)] + re.findall(r'"([^"]+)"', m.group(3)):
            t = title.strip().rstrip("\\").lower()
            if not any(t in h for h in known[name]):
                bad += 1
                print(f'{path}: {name} "{title}" names no heading of {markdown[name]}')
print(f"{bad} reference(s) to a missing section" if bad else "every section reference names a heading")
sys.exit(1 if bad else 0)
