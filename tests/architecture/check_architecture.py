#!/usr/bin/python3
"""Structural checks of the source tree (docs/architecture.md):

- layers: a folder of include/gaitopt/ and src/ includes only from folders of lower layers
  (peers of one layer do not include each other), so no two folders include each other;
- front end: every src/cli/*.cpp is at most 200 lines (the CLI parses, calls and writes);
- one solver status: the text "optimal" is compared in at most two places (its to/from-text
  functions), the rest of the code compares the enum.

Usage: check_architecture.py SOURCE_DIR. Prints every violation; exit 1 if any.
"""
import pathlib
import re
import sys

# Bottom to top; a folder may include from folders of a strictly lower layer only.
LAYERS = {
    "math": 0, "model": 1, "impact": 2, "gait": 3, "opt": 4, "control": 4,
    "sim": 5, "ident": 5, "io": 6, "export": 7, "cli": 8, "capi": 8,
}
MAX_CLI_LINES = 200
MAX_STATUS_TEXT_COMPARES = 2

INCLUDE = re.compile(r'^\s*#\s*include\s+"gaitopt/([a-z_]+)/', re.M)
STATUS_COMPARE = re.compile(r'[!=]=\s*"optimal"|"optimal"\s*[!=]=')


def folder_of(root, path):
    rel = path.relative_to(root).parts
    if rel[0] == "include":
        return rel[2]
    return rel[1]  # src/<folder>/...


def sources(root):
    for base in (root / "include" / "gaitopt", root / "src"):
        for path in sorted(base.rglob("*")):
            if path.suffix in (".hpp", ".cpp", ".h"):
                yield path


def layer_violations(root):
    found = []
    for path in sources(root):
        folder = folder_of(root, path)
        if folder not in LAYERS:
            found.append(f"{path.relative_to(root)}: folder '{folder}' has no layer in LAYERS")
            continue
        for target in INCLUDE.findall(path.read_text(encoding="utf-8")):
            if target == folder:
                continue
            if target not in LAYERS:
                found.append(f"{path.relative_to(root)}: includes unknown folder '{target}'")
            elif LAYERS[target] >= LAYERS[folder]:
                found.append(f"{path.relative_to(root)}: {folder} (layer {LAYERS[folder]}) "
                             f"includes {target} (layer {LAYERS[target]})")
    return found


def cli_violations(root):
    found = []
    for path in sorted((root / "src" / "cli").glob("*.cpp")):
        lines = len(path.read_text(encoding="utf-8").splitlines())
        if lines > MAX_CLI_LINES:
            found.append(f"{path.relative_to(root)}: {lines} lines, more than {MAX_CLI_LINES}")
    return found


def status_violations(root):
    places = []
    for base in ("include", "src", "bench", "python"):
        for path in sorted((root / base).rglob("*")):
            if path.suffix in (".hpp", ".cpp"):
                for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                    if STATUS_COMPARE.search(line):
                        places.append(f"{path.relative_to(root)}:{n}")
    if len(places) > MAX_STATUS_TEXT_COMPARES:
        return [f'the status text "optimal" is compared in {len(places)} places (at most '
                f'{MAX_STATUS_TEXT_COMPARES}): ' + ", ".join(places)]
    return []


def main():
    if len(sys.argv) != 2:
        print("usage: check_architecture.py SOURCE_DIR", file=sys.stderr)
        return 2
    root = pathlib.Path(sys.argv[1]).resolve()
    violations = layer_violations(root) + cli_violations(root) + status_violations(root)
    for v in violations:
        print("architecture:", v)
    print(f"architecture: {len(violations)} violation(s)")
    return 1 if violations else 0


if __name__ == "__main__":
    sys.exit(main())
