#!/usr/bin/python3
"""The user documentation stays true: README.md and every page under docs/.

Usage: check_docs.py SOURCE_DIR BUILD_DIR

Checks, each failure reported with its page and line:
- every ```sh block runs: the pages are run one after the other, each in a fresh sandbox folder
  (symbolic links to the source tree's configs/, data/, scripts/, examples/ and to the build
  folder as build/, an empty results/), its blocks in order as one bash script each
  (`set -euo pipefail`), so a block may use what an earlier block of its page wrote. Lines that
  build, install, benchmark, fuzz or run the whole suite (the BUILD_COMMANDS below: they take
  minutes or recurse into this test) are not run; their program must exist instead (a script
  or binary of the tree, or a tool on PATH);
- the README has at most 400 lines; a table starts with a header row and its separator;
- every relative link points to an existing file;
- no page speaks of the project's history (sessions, issue numbers).
Blocks fenced ``` without an info string are synopses or diagrams and are not run.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

# Programs whose lines are checked for existence, not run (see above).
BUILD_COMMANDS = {"cmake", "ctest", "scripts/run.sh", "scripts/test.sh", "scripts/setup.sh",
                  "scripts/build_san.sh", "scripts/fuzz.sh", "scripts/measure_acceptance.sh",
                  "scripts/regenerate_gaits.sh"}
# Scripts that, without arguments, regenerate a page's figures over minutes: checked like the
# build commands then (with arguments they are run).
REGENERATORS = {"scripts/mujoco_grid.sh"}
SANDBOX_LINKS = ["configs", "data", "scripts", "examples", "tests"]
BLOCK_TIMEOUT_S = 900
HISTORY = re.compile(r"\b(session|sessions)\b|\bissue \d+|\bitem \d+ of", re.IGNORECASE)

failures = []


def fail(page, line, message):
    failures.append(f"{page}:{line}: {message}")


def pages(source):
    found = ["README.md"]
    for root, _, files in os.walk(os.path.join(source, "docs")):
        found += [os.path.relpath(os.path.join(root, f), source) for f in files if f.endswith(".md")]
    return sorted(found, key=lambda p: (p != "README.md", p))


def blocks(lines):
    """(info string, first line number, body lines) of each fenced block."""
    result, inside, info, start, body = [], False, "", 0, []
    for i, line in enumerate(lines, 1):
        if line.startswith("```"):
            if inside:
                result.append((info, start, body))
            else:
                info, start, body = line[3:].strip(), i + 1, []
            inside = not inside
        elif inside:
            body.append(line)
    return result


def commands(body):
    """The logical lines of a block: continuations joined, blank lines dropped."""
    joined, current = [], ""
    for line in body:
        current += line.rstrip("\\").rstrip() + " " if line.endswith("\\") else line
        if not line.endswith("\\"):
            if current.strip():
                joined.append(current)
            current = ""
    return joined


def program(command):
    words = command.split("#", 1)[0].split()
    while words and re.match(r"^[A-Za-z_][A-Za-z0-9_]*=", words[0]):
        words.pop(0)
    return words[0] if words else ""


def check_program_exists(page, line, name, sandbox):
    if name.startswith("build/bench/"):  # built with the project's default target
        ok = os.path.isdir(os.path.join(sandbox, "build", "bench"))
    elif "/" in name:
        ok = os.path.exists(os.path.join(sandbox, name))
    else:
        ok = shutil.which(name) is not None
    if not ok:
        fail(page, line, f"{name}: named by the docs but not found")


def make_sandbox(source, build):
    sandbox = tempfile.mkdtemp(prefix="gaitopt-docs-")
    for name in SANDBOX_LINKS:
        os.symlink(os.path.join(source, name), os.path.join(sandbox, name))
    os.symlink(build, os.path.join(sandbox, "build"))
    os.mkdir(os.path.join(sandbox, "results"))
    return sandbox


def run_block(page, start, body, sandbox, prelude):
    """Runs the block after `prelude` (the assignments of the page's earlier blocks, as in one
    shell session); appends its own assignments to it."""
    script = ["set -euo pipefail"] + prelude
    ran = 0
    for command in commands(body):
        name = program(command)
        bare = len(command.split("#", 1)[0].split()) == 1
        if not name:
            script.append(command)  # a comment or an assignment
            if command.split("#", 1)[0].strip():
                prelude.append(command)
        elif name in BUILD_COMMANDS or name.startswith("build/bench/") or (
                bare and name in REGENERATORS):
            check_program_exists(page, start, name, sandbox)
        else:
            script.append(command)
            ran += 1
    if ran == 0:
        return 0
    proc = subprocess.run(["bash", "-c", "\n".join(script)], cwd=sandbox, capture_output=True,
                          text=True, timeout=BLOCK_TIMEOUT_S)
    if proc.returncode != 0:
        tail = (proc.stdout[-1500:] + "\n" + proc.stderr[-1500:]).strip()
        fail(page, start, f"the block exits {proc.returncode}:\n{tail}")
    return ran


def check_text(page, lines, source):
    inside = False
    for i, line in enumerate(lines, 1):
        if line.startswith("```"):
            inside = not inside
            continue
        if inside:
            continue
        if line.startswith("|") and (i == 1 or not lines[i - 2].startswith("|")):
            if i >= len(lines) or not re.match(r"^\|[-| :]+\|$", lines[i]):
                fail(page, i, "a table without its header row and separator")
        for m in re.finditer(r"\]\(([^)#\s]+)(#[^)]*)?\)", line):
            target = m.group(1)
            if re.match(r"^[a-z]+://", target):
                continue
            if not os.path.exists(os.path.join(source, os.path.dirname(page), target)):
                fail(page, i, f"link to a missing file: {target}")
        if HISTORY.search(line.replace("first session", "")):
            fail(page, i, f"speaks of the project's history: {line.strip()[:80]}")


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    source, build = (os.path.abspath(a) for a in sys.argv[1:])
    total_blocks = total_commands = 0
    for page in pages(source):
        lines = open(os.path.join(source, page), encoding="utf-8").read().split("\n")
        check_text(page, lines, source)
        if page == "README.md" and len(lines) > 400:
            fail(page, len(lines), f"the README has {len(lines)} lines (at most 400)")
        runnable = [(s, b) for info, s, b in blocks(lines) if info == "sh"]
        if not runnable:
            continue
        sandbox = make_sandbox(source, build)
        prelude = []
        try:
            for start, body in runnable:
                ran = run_block(page, start, body, sandbox, prelude)
                total_blocks += ran > 0
                total_commands += ran
        finally:
            shutil.rmtree(sandbox, ignore_errors=True)
    print(f"check_docs: {total_commands} commands in {total_blocks} blocks run")
    if total_commands < 20:
        fail("docs", 0, f"only {total_commands} commands run: the docs lost their examples")
    for f in failures:
        print(f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
