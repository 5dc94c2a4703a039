#!/usr/bin/env python3
"""Layout limits of issue 27: no source file over MAX_FILE lines outside tests, no function over MAX_FN lines.

Usage: scripts/layout-check.py [--files-only] DIR...
--files-only checks the file limit alone (the core, whose hot loops are long by design).
A function may be longer when the line before its `fn` (or its doc comment) holds `layout: long`, with the
reason on the same line (a hot loop). Function length is counted from the `fn` line to its closing brace,
which rustfmt puts at the `fn` line's indentation. Files under tests/ or named tests.rs are skipped, and so
is everything after a top-level `#[cfg(test)]` line (unit tests).
"""
import os, re, sys

MAX_FILE, MAX_FN = 800, 100
FN = re.compile(r"^(\s*)(pub(\([^)]*\))?\s+)?(const\s+)?(async\s+)?(unsafe\s+)?(extern\s+\"[^\"]*\"\s+)?fn\s+(\w+)")

def check(path, files_only):
    lines = open(path, encoding="utf-8").read().split("\n")
    end = len(lines) - (lines[-1] == "")
    for i, line in enumerate(lines):
        if line.startswith("#[cfg(test)]"):
            end = i
            break
    problems = []
    if end > MAX_FILE:
        problems.append(f"{path}: {end} lines (limit {MAX_FILE}, tests excluded)")
    for i in range(0 if not files_only else end, end):
        m = FN.match(lines[i])
        if not m:
            continue
        indent = m.group(1)
        # a declaration without a body (trait method) ends with ';' before any '{'
        j = i
        while j < end and "{" not in lines[j] and not lines[j].rstrip().endswith(";"):
            j += 1
        if j >= end or "{" not in lines[j]:
            continue
        if lines[j].rstrip().endswith("}"):
            continue  # one-line body
        k = j + 1
        while k < end and lines[k] != indent + "}":
            k += 1
        length = k - i + 1
        allowed = any("layout: long" in lines[p] for p in range(max(0, i - 8), i))
        if length > MAX_FN and not allowed:
            problems.append(f"{path}:{i + 1}: fn {m.group(8)} is {length} lines (limit {MAX_FN})")
    return problems

def main(argv):
    files_only = "--files-only" in argv
    dirs = [a for a in argv if not a.startswith("--")]
    problems = []
    for d in dirs:
        for root, _, files in os.walk(d):
            if "/tests" in root or root.endswith("tests") or "/target" in root:
                continue
            for f in sorted(files):
                if f.endswith(".rs") and f != "tests.rs":
                    problems += check(os.path.join(root, f), files_only)
    for p in problems:
        print(p)
    print(f"layout-check: {len(problems)} problem(s) in {', '.join(dirs)}")
    return 1 if problems else 0

sys.exit(main(sys.argv[1:]))
