#!/usr/bin/python3
"""check_architecture.py finds each kind of violation in a small planted tree, by its message,
and passes a tree without them."""
import pathlib
import subprocess
import sys
import tempfile

CHECK = pathlib.Path(__file__).with_name("check_architecture.py")


def write(root, rel, text):
    path = root / rel
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")


def run(root):
    r = subprocess.run([sys.executable, str(CHECK), str(root)], capture_output=True, text=True)
    return r.returncode, r.stdout


def clean_tree(root):
    write(root, "include/gaitopt/math/a.hpp", "#pragma once\n")
    write(root, "include/gaitopt/gait/b.hpp", '#include "gaitopt/math/a.hpp"\n')
    write(root, "src/io/c.cpp", '#include "gaitopt/gait/b.hpp"\n')
    write(root, "src/cli/main.cpp", "int main() {}\n" * 200)
    write(root, "src/opt/status.cpp", 'bool f(const char* s) { return s == "optimal"; }\n')
    for d in ("bench", "python"):
        (root / d).mkdir(exist_ok=True)


def main():
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        clean_tree(root)
        code, out = run(root)
        if code != 0 or "0 violation(s)" not in out:
            failures.append(f"clean tree: exit {code}, output {out!r}")
        write(root, "src/gait/d.cpp", '#include "gaitopt/io/x.hpp"\n')
        write(root, "src/opt/e.cpp", '#include "gaitopt/sim/y.hpp"\n')
        write(root, "src/cli/big.cpp", "//\n" * 201)
        write(root, "bench/b.cpp", 'x == "optimal";\ny != "optimal";\n')
        write(root, "src/widgets/w.cpp", "\n")
        code, out = run(root)
        expected = [
            "src/gait/d.cpp: gait (layer 3) includes io (layer 6)",
            "src/opt/e.cpp: opt (layer 4) includes sim (layer 5)",
            "src/cli/big.cpp: 201 lines, more than 200",
            'the status text "optimal" is compared in 3 places (at most 2)',
            "src/widgets/w.cpp: folder 'widgets' has no layer in LAYERS",
            "5 violation(s)",
        ]
        if code != 1:
            failures.append(f"planted tree: exit {code}, expected 1")
        failures += [f"planted tree: no line with {e!r} in {out!r}" for e in expected if e not in out]
    for f in failures:
        print("FAIL:", f)
    if not failures:
        print("check_architecture: the clean tree passes, every planted violation is named")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
