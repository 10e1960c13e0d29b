#!/usr/bin/env python3
"""Holds the docs to the sizes a reader can use (run by `make test`):

- README.md and ARCHITECTURE.md at most 150 lines each;
- docs/performance.md at most 25,000 bytes;
- no line of README.md, ARCHITECTURE.md, CONTRIBUTING.md or docs/*.md over 400
  characters (tables and code included).

Prints each fault with its file and line, and exits 1 when there is one.
`check-docs.py FILE...` checks only the line lengths of the files named."""

import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
MAX_LINE = 400
MAX_LINES = {"README.md": 150, "ARCHITECTURE.md": 150}
MAX_BYTES = {"docs/performance.md": 25_000}


def long_lines(path):
    """(line number, length) of each line of `path` over MAX_LINE characters."""
    text = path.read_text(encoding="utf-8")
    return [(n, len(l)) for n, l in enumerate(text.splitlines(), 1) if len(l) > MAX_LINE]


def main(args):
    faults = []
    if args:
        files = [pathlib.Path(a) for a in args]
    else:
        files = [ROOT / n for n in ("README.md", "ARCHITECTURE.md", "CONTRIBUTING.md")]
        files += sorted((ROOT / "docs").glob("*.md"))
        for name, most in MAX_LINES.items():
            lines = len((ROOT / name).read_text(encoding="utf-8").splitlines())
            if lines > most:
                faults.append(f"{name}: {lines} lines, more than {most}")
        for name, most in MAX_BYTES.items():
            size = (ROOT / name).stat().st_size
            if size > most:
                faults.append(f"{name}: {size} bytes, more than {most}")
    for path in files:
        shown = path.relative_to(ROOT) if path.is_absolute() and ROOT in path.parents else path
        for n, length in long_lines(path):
            faults.append(f"{shown}:{n}: a line of {length} characters, more than {MAX_LINE}")
    for f in faults:
        print(f, file=sys.stderr)
    if faults:
        print(f"check-docs: {len(faults)} fault(s)", file=sys.stderr)
        return 1
    print(f"check-docs: {len(files)} files within their sizes")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
