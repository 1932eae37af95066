#!/usr/bin/python3
"""Every figure the documentation quotes comes from a script that regenerates it.

Usage: check_figures.py SOURCE_DIR BUILD_DIR
       check_figures.py --self-test

Checks README.md and every page under docs/ (generated blocks: scripts/docs_blocks.py):
1. the markers are well formed (begin/end pairs, no nesting, keys unique per page);
2. every block names a script that exists and lists the block (`bash SCRIPT --blocks`), and
   every block a script lists exists;
3. the cheap regenerators (CHEAP below: seconds to a minute) are run into a copy of the pages
   with their blocks emptied (GAITOPT_DOCS_ROOT): the copy must come back equal to the tree,
   so a block its script no longer writes, or figures that are not reproduced, fail. The other
   regenerators (minutes or hours) are checked by 1 and 2 only;
4. no page quotes a measured figure outside a generated block. A measured figure is, in prose
   or a table, outside code spans, fenced blocks and link targets:
   - a number with a unit of time or memory (`1.46 s`, `20 ms`, `9.5 MiB`);
   - a percentage (`0.18 %`);
   - a value of a criterion: a number with the unit N²·m·s or J/m, or a decimal number right
     after C_Γ, C_Gamma, C_E or CoT (`C_Γ = 9122.8`, `C_Γ 10559.29`);
   - a number in scientific form with a mantissa (`2.9·10⁻⁵`; a bare power of ten is a
     tolerance);
   - a decimal number with four or more significant digits in a table (`12132.23`).
   Not measured: an equation reference such as (3.147); a number right after a word that
   makes it a bound or a setting (within, below, above, at most, at least, up to, less/more
   than, <, >, ≤, ≥, ±, default, tolerance, limit, target, bound, every, period); the
   constants of ALLOWED below.
   Pages in EXCLUDED (rewritten elsewhere) and CONSTANT_PAGES (numbers that are constants,
   such as the tests' inputs and tolerances) are not scanned; a page in PENDING quotes
   exactly its count of such figures by hand (so the count can only go down, and is lowered
   as it does).
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

# Regenerators run by check 3 (seconds to a minute each on 2 cores; docs/tests.md).
CHEAP = {"scripts/sweep_table.sh", "scripts/export_figures.sh", "scripts/evaluation_accuracy.sh",
         "scripts/friction_figures.sh", "scripts/ramp_table.sh", "scripts/simulate_figures.sh",
         "scripts/shipped_gaits.sh", "scripts/impact_figures.sh",
         "scripts/opensim_import_figures.sh"}
# Pages rewritten elsewhere at the moment; not scanned until they are converted.
EXCLUDED: set = set()
# Pages whose numbers are constants, not measurements: not scanned (page -> why).
CONSTANT_PAGES = {
    "docs/tests.md": "what each test asserts: its inputs and tolerances, read from its source",
}
# Pages still quoting measured figures by hand, with how many: the count may only go down.
PENDING = {}
# Constants of the specification, settings of the tool and figures of the literature that
# look like measured figures, as written on any page (or on the page named before a colon)
# -> what they are.
ALLOWED = {
    "1 ms": "the period of the 1 kHz samples (export, controller, trajectory.csv)",
    "0.5 ms": "the MuJoCo time step of the exported MJCF",
    "5 ms": "the assumed duration of a held impact (simulate --impact double_support)",
    "10 ms": "the contact duration of a rubber-padded foot, the reason for the 5 ms",
    "20 ms": "the walker's settings: a foot off the ground this long is a contact change",
    "0.1 s": "the walker's setting: no foot on the ground this long is a fall",
    "0.02 s": "the duration of mujoco_walk --push",
    "0.5 s": "the margin of the stall check, 3 (T_SS + T_DS) + 0.5 s",
    "1 MiB": "reader limit (docs/reliability.md)",
    "4 KiB": "reader limit (docs/reliability.md)",
    "4 MiB": "reader limit (docs/reliability.md)",
    "64 MiB": "reader limit (docs/reliability.md)",
    "25 %": "the friction margin: μ = 0.6 planned against the plant's 0.8",
    "0.30000000000000004": "0.2 + 0.1 in binary floating point, the rounding sweep avoids",
    "0.1 %": "the clustering tolerance of random starts and global search",
    "30 %": "the walker's least normal force in double support, a fraction of the weight",
    "docs/commands/export.md: 2 %": "the ramp search's margin, a fraction of each scale",
    "docs/commands/export.md: 1 %": "the ramp check's tolerance on a positive level",
    "docs/reliability.md: 10 s": "the age of a stale lock; the fuzzers' hang limit",
    "docs/reliability.md: 20 s": "the fuzz smoke run's seconds per harness (FUZZ_SECONDS)",
    "docs/reliability.md: 45 min": "the CI time budget",
    "docs/benchmarks.md: 2 h": "the thesis' time per optimisation (literature)",
    "docs/benchmarks.md: 1.5 s": "TROPIC's published time per gait (literature)",
    "docs/commands/diagnose.md: 217.5": "synth's generation range of payload, 10 × the admissible 21.75 kg",
    "docs/commands/diagnose.md: 50 %": "the admissible payload, a fraction of the robot's mass",
    "docs/commands/diagnose.md: 20 %": "the held-out gain a cause must reach (a setting)",
    "docs/commands/diagnose.md: 5 %": "settings: min_inertial_gain, the signature's share of the signal",
    "docs/commands/diagnose.md: 90 %": "the share of the change that picks the channels a cause acts on",
    "docs/commands/diagnose.md: 95 %": "the confidence level of the leave-one-step-out interval",
}

NUM = r"(?<![\w.·⁻/])\d+(?:\.\d+)?"
SUPERSCRIPT = "⁰¹²³⁴⁵⁶⁷⁸⁹"
PATTERNS = [
    ("time or memory", re.compile(NUM + r"\s?(?:s|ms|µs|min|h|MiB|KiB|GiB|MB|kB)(?![\w²/·*^⁻])")),
    ("percentage", re.compile(NUM + r"\s?%")),
    ("criterion", re.compile(NUM + r"\s?(?:N²·m·s|N\^2\*m\*s|J/m)")),
    ("criterion", re.compile(r"(?:C_Γ|C_Gamma|C_E|CoT)\s?[=≈:]?\s?\*?\d+\.\d+")),
    ("mantissa", re.compile(r"(?<![\w.])\d+(?:\.\d+)?\s?[·×]\s?10⁻?[" + SUPERSCRIPT + "]+")),
]
TABLE_NUMBER = re.compile(r"(?<![\w.·⁻])\d+\.\d+(?![\w.])")
BOUND = re.compile(r"(?:within|below|above|at most|at least|up to|less than|more than|<|>|≤|≥|±|"
                   r"default|tolerance|tol|limit|target|bound|every|period)\W{0,3}$", re.I)
EQUATION = re.compile(r"\((?:[A-Z]|\d{1,2})\.\d{1,3}\)")  # a thesis equation, (3.147)

failures = []


def fail(where, message):
    failures.append(f"{where}: {message}")


def significant_digits(number):
    return len(number.replace(".", "").lstrip("0"))


def measured_figures(page, lines):
    """(line number, kind, figure) of every measured figure outside generated blocks."""
    import docs_blocks
    found, fenced, generated = [], False, False
    for i, line in enumerate(lines, 1):
        if line.startswith("```"):
            fenced = not fenced
            continue
        if fenced:
            continue
        marker = docs_blocks.MARKER.match(line.rstrip())
        if marker:
            generated = marker.group(2) == "begin"
        if marker or generated:
            continue
        text = re.sub(r"\]\([^)]*\)", "]", re.sub(r"`[^`]*`", "", line))
        text = EQUATION.sub("", text)
        candidates = [(m, kind) for kind, p in PATTERNS for m in p.finditer(text)]
        if text.startswith("|"):
            found += [(i, "table value", m.group(0)) for m in TABLE_NUMBER.finditer(text)
                      if significant_digits(m.group(0)) >= 4 and m.group(0) not in ALLOWED
                      and f"{page}: {m.group(0)}" not in ALLOWED]
        for m, kind in candidates:
            if BOUND.search(text[:m.start()][-16:]):
                continue
            figure = m.group(0).strip()
            if figure in ALLOWED or f"{page}: {figure}" in ALLOWED:
                continue
            found.append((i, kind, figure))
    return found


def check_scan(source):
    import docs_blocks
    for page in docs_blocks.pages(source):
        if page in EXCLUDED or page in CONSTANT_PAGES:
            continue
        figures = measured_figures(page, docs_blocks.read_lines(source, page))
        allowed = PENDING.get(page, 0)
        if len(figures) > allowed:
            shown = figures if allowed == 0 else figures[:3]
            fail(page, f"{len(figures)} measured figures outside a generated block "
                       f"(at most {allowed}): "
                       + "; ".join(f"line {i}: {kind} '{fig}'" for i, kind, fig in shown))
        elif len(figures) < allowed:
            fail(page, f"{len(figures)} measured figures outside a generated block: lower its "
                       f"PENDING count from {allowed} (or remove the page when 0)")


def listed_blocks(source, script):
    proc = subprocess.run(["bash", os.path.join(source, script), "--blocks"], cwd=source,
                          capture_output=True, text=True, timeout=60)
    if proc.returncode != 0:
        return None
    return {tuple((line.split() + [""])[:2]) for line in proc.stdout.splitlines() if line.strip()}


def check_blocks(source):
    import docs_blocks
    try:
        found = docs_blocks.all_blocks(source)
    except docs_blocks.BlockError as e:
        fail("markers", str(e))
        return []
    scripts = sorted({b["script"] for b in found} | CHEAP)
    for script in scripts:
        mine = {(b["page"], b["key"]) for b in found if b["script"] == script}
        if not os.path.isfile(os.path.join(source, script)):
            fail(script, "named by a generated block but does not exist")
            continue
        listed = listed_blocks(source, script)
        if listed is None:
            fail(script, "does not answer --blocks")
            continue
        for page, key in sorted(mine - listed):
            fail(f"{page}", f"block {key or '(no key)'} names {script}, which does not write it")
        for page, key in sorted(listed - mine):
            fail(f"{page}", f"{script} writes block {key or '(no key)'}, missing from the page")
    return found


def emptied_copy(source, found):
    """README.md and docs/ copied to a temporary folder, the blocks of CHEAP emptied."""
    import docs_blocks
    copy = tempfile.mkdtemp(prefix="gaitopt-figures-")
    shutil.copytree(os.path.join(source, "docs"), os.path.join(copy, "docs"))
    shutil.copy(os.path.join(source, "README.md"), copy)
    for page in sorted({b["page"] for b in found if b["script"] in CHEAP}):
        lines = docs_blocks.read_lines(copy, page)
        for b in reversed(docs_blocks.blocks(page, lines)):
            if b["script"] in CHEAP:
                lines = lines[:b["begin"] + 1] + lines[b["end"]:]
        with open(os.path.join(copy, page), "w", encoding="utf-8") as f:
            f.write("\n".join(lines))
    return copy


def check_regeneration(source, build, found):
    import docs_blocks
    copy = emptied_copy(source, found)
    env = dict(os.environ, GAITOPT_DOCS_ROOT=copy, GAITOPT=os.path.join(build, "gaitopt"),
               GAITOPT_RESULTS=os.path.join(copy, "results"))
    try:
        for script in sorted(CHEAP):
            proc = subprocess.run(["bash", os.path.join(source, script)], cwd=source, env=env,
                                  capture_output=True, text=True, timeout=600)
            if proc.returncode != 0:
                fail(script, f"exits {proc.returncode}: {proc.stderr.strip()[-800:]}")
        for page in docs_blocks.pages(source):
            want = docs_blocks.read_lines(source, page)
            got = docs_blocks.read_lines(copy, page)
            if want != got:
                diff = [f"line {i + 1}: docs '{a[:100]}' / regenerated '{b[:100]}'"
                        for i, (a, b) in enumerate(zip(want, got)) if a != b][:4]
                fail(page, "its generated blocks differ from what their script writes now "
                           f"(run the script named in the block): {'; '.join(diff) or 'lengths'}")
    finally:
        shutil.rmtree(copy, ignore_errors=True)


def self_test():
    """The scan finds what it is meant to and nothing else (so that the check can fail)."""
    sample = ["The sweep takes 1.46 s and 9.5 MiB; C_Γ = 9122.8 (+0.18 %), off by 2.9·10⁻⁵.",
              "| v [m/s] | 0.2 |", "|---|---|", "| C_Γ | 12132.23 |",
              "Within 5 %, at most 10⁻⁶, default 0.35 s, `12.3 s` in code, [a](x_1.5s.md).",
              "<!-- generated by scripts/x.sh: begin -->", "took 3.5 s", "<!-- generated by scripts/x.sh: end -->",
              "```", "took 4.5 s", "```"]
    import docs_blocks
    for bad in (["<!-- generated by scripts/x.sh: begin -->"],
                ["<!-- generated by scripts/x.sh: end -->"],
                ["<!-- generated by scripts/x.sh: begin a -->", "<!-- generated by scripts/x.sh: end b -->"],
                ["<!-- generated by scripts/x.sh begin -->"]):
        try:
            docs_blocks.blocks("self-test.md", bad)
            fail("self-test", f"markers accepted: {bad}")
        except docs_blocks.BlockError:
            pass
    got = [(i, fig) for i, _, fig in measured_figures("self-test.md", sample)]
    want = [(1, "1.46 s"), (1, "9.5 MiB"), (1, "0.18 %"), (1, "C_Γ = 9122.8"), (1, "2.9·10⁻⁵"),
            (4, "12132.23")]
    if sorted(got) != sorted(want):
        fail("self-test", f"measured figures found {sorted(got)}, expected {sorted(want)}")


def main(argv):
    source = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    if len(argv) == 3:
        source = os.path.abspath(argv[1])
    sys.path.insert(0, os.path.join(source, "scripts"))
    self_test()
    if argv[1:] == ["--self-test"]:
        pass
    elif len(argv) == 3:
        build = os.path.abspath(argv[2])
        found = check_blocks(source)
        check_scan(source)
        if not failures:
            check_regeneration(source, build, found)
        print(f"check_figures: {len(found)} generated blocks, {len(CHEAP)} regenerated; "
              f"{len(PENDING)} pages pending conversion, {len(EXCLUDED)} excluded")
    else:
        print(__doc__, file=sys.stderr)
        return 2
    for f in failures:
        print(f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
