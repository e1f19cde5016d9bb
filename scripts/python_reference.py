#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The Python API reference, docs/reference/python.md, made from the
module's own docstrings: every public function, class, method and property
of `tumble` and `tumble.io`, the compiled part (src/python/*.cpp) and the
Python part (src/python/tumble/*.py) alike. The page is generated, never
edited by hand: the ctest `python_reference` fails when the module and the
page differ, or when a public name has no docstring, and says how to write
the page again.

    python3 scripts/python_reference.py build/python --write   # write the page
    python3 scripts/python_reference.py build/python --check   # exit 1 if it differs

build/python: the directory that holds the built package (PYTHONPATH).
Standard library only (and the package's numpy and pandas).
"""
import importlib
import inspect
import os
import re
import sys
import textwrap

from generated_page import write_or_check

PAGE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "reference", "python.md")
MODULES = ("tumble", "tumble.io")


def doc_of(obj):
    """The docstring without the signatures pybind11 puts first; '' if none."""
    text = inspect.cleandoc(getattr(obj, "__doc__", None) or "")
    name = getattr(obj, "__name__", "")
    if name and text.startswith(name + "("):
        text = text.split("\n", 1)[1] if "\n" in text else ""
    # pybind11's docstrings are one line each: wrapped as the Python ones are
    return "\n".join(textwrap.fill(line, 79) if len(line) > 79 else line for line in text.strip().splitlines())


def signature(obj, name):
    """The call's signature: Python's own, or the one pybind11 wrote into the docstring."""
    try:
        return f"{name}{inspect.signature(obj)}"
    except (TypeError, ValueError):
        first = inspect.cleandoc(obj.__doc__ or "").split("\n", 1)[0]
        sig = first[len(obj.__name__):] if first.startswith(obj.__name__ + "(") else "(...)"
        return name + re.sub(r"self: [\w.]+(, )?", "", sig)


def block(language, text):
    return [f"```{language}", text, "```", ""] if text else []


def public(namespace):
    return [(n, v) for n, v in namespace.items() if not n.startswith("_")]


def members(cls):
    """(name, member) of a class: its constructor where it has one, then its
    own public methods and properties, in the order they are defined."""
    out = []
    init = cls.__dict__.get("__init__")
    if init is not None and (inspect.isfunction(init) or "__init__(" in (init.__doc__ or "")):
        out.append(("__init__", init))
    return out + [(n, v if isinstance(v, property) else getattr(cls, n)) for n, v in public(vars(cls))]


def document(module, lines, missing):
    """Appends the module's section; names what has no docstring to `missing`."""
    name = module.__name__
    lines += [f"## `{name}`", ""] + block("text", doc_of(module))
    own = [(n, v) for n, v in public(vars(module)) if (getattr(v, "__module__", None) or "").startswith("tumble")]
    kinds = (("Functions", lambda v: callable(v) and not inspect.isclass(v)), ("Classes", inspect.isclass))
    for title, keep in kinds + (("Data", None),):
        chosen = sorted(own if keep else [(n, v) for n, v in public(vars(module)) if isinstance(v, (dict, tuple))])
        chosen = [(n, v) for n, v in chosen if keep is None or keep(v)]
        if not chosen:
            continue
        lines += [f"### {title}", ""]
        for n, v in chosen:
            full = f"{name}.{n}"
            lines += [f"#### `{full}`", ""]
            if title == "Data":
                lines += block("python", f"{n} = {v!r}")
                continue
            if title == "Functions":
                lines += block("python", signature(v, n))
            lines += block("text", doc_of(v))
            if not doc_of(v):
                missing.append(full)
            if title == "Classes":
                for m, member in members(v):
                    what = f"{n}.{m}"
                    if isinstance(member, property):
                        lines += [f"##### `{what}`" + ("" if member.fset else " (read-only)"), ""]
                    else:
                        lines += [f"##### `{what}()`", ""] + block("python", signature(member, what))
                    text = doc_of(member)
                    lines += block("text", text)
                    if not text and m != "__init__":
                        missing.append(f"{name}.{what}")


def page(missing):
    lines = [
        "# Python API: `tumble` and `tumble.io`",
        "",
        "This page is made from the module's own docstrings "
        "(`python3 scripts/python_reference.py build/python --write`); the test "
        "`python_reference` fails when the two differ, or when a public name has "
        "no docstring. The same text is printed by `help(tumble)` and "
        "`help(tumble.io)`. A first walk through: [From Python](../tutorials/python.md).",
        "",
    ]
    for name in MODULES:
        document(importlib.import_module(name), lines, missing)
    return "\n".join(lines).rstrip() + "\n"


def main():
    if len(sys.argv) != 3 or sys.argv[2] not in ("--write", "--check"):
        sys.exit(__doc__)
    sys.path.insert(0, os.path.abspath(sys.argv[1]))
    missing = []
    made = page(missing)
    for name in missing:
        print(f"{name}: no docstring")
    status = write_or_check(PAGE, made, sys.argv[2], "the module's docstrings",
                            "python3 scripts/python_reference.py build/python --write")
    return 1 if missing else status

if __name__ == "__main__":
    sys.exit(main())
