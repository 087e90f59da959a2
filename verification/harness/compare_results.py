#!/usr/bin/python3
"""Compare two verification result.json files (schema in verification/README.md).

Usage:
    /usr/bin/python3 verification/harness/compare_results.py A/result.json B/result.json [--notes]

Compares the case, tier and status; the checks by name (value, threshold, comparison,
expected, gating, passed) and their order; and the metrics recursively. Wall times
(keys containing "wall") are ignored. Notes (the checks' and the result's) are ignored
unless --notes is given. Numbers must be equal exactly. Exit status 0 when the two
files agree, 1 otherwise (each difference is printed).
"""

from __future__ import annotations

import json
import math
import sys

CHECK_FIELDS = ("value", "threshold", "comparison", "expected", "gating", "passed")


def same(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return a == b
    return a == b


def compare_tree(a, b, path: str, out: list[str]) -> None:
    if isinstance(a, dict) and isinstance(b, dict):
        for key in sorted(set(a) | set(b)):
            if "wall" in key:
                continue
            where = f"{path}.{key}" if path else key
            if key not in a:
                out.append(f"{where}: only in B ({b[key]!r})")
            elif key not in b:
                out.append(f"{where}: only in A ({a[key]!r})")
            else:
                compare_tree(a[key], b[key], where, out)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{path}: {len(a)} items in A, {len(b)} in B")
        for i, (x, y) in enumerate(zip(a, b)):
            compare_tree(x, y, f"{path}[{i}]", out)
    elif not same(a, b):
        out.append(f"{path}: A {a!r}, B {b!r}")


def compare(a: dict, b: dict, notes: bool) -> list[str]:
    out: list[str] = []
    for key in ("case", "tier", "status", "title", "seed_section", "figures"):
        if a.get(key) != b.get(key):
            out.append(f"{key}: A {a.get(key)!r}, B {b.get(key)!r}")
    checks_a = {c["name"]: c for c in a.get("checks", [])}
    checks_b = {c["name"]: c for c in b.get("checks", [])}
    for name in checks_a.keys() - checks_b.keys():
        out.append(f"check only in A: {name}")
    for name in checks_b.keys() - checks_a.keys():
        out.append(f"check only in B: {name}")
    for name in checks_a.keys() & checks_b.keys():
        for field in CHECK_FIELDS + (("note",) if notes else ()):
            x, y = checks_a[name].get(field), checks_b[name].get(field)
            if not same(x, y) and not (isinstance(x, list) and x == y):
                out.append(f"check {name!r} {field}: A {x!r}, B {y!r}")
    order_a = [c["name"] for c in a.get("checks", [])]
    order_b = [c["name"] for c in b.get("checks", [])]
    if set(order_a) == set(order_b) and order_a != order_b:
        out.append("checks: same names in a different order")
    compare_tree(a.get("metrics", {}), b.get("metrics", {}), "metrics", out)
    if notes and a.get("notes") != b.get("notes"):
        out.append("notes differ")
    return out


def main(argv: list[str]) -> int:
    args = [x for x in argv[1:] if not x.startswith("--")]
    if len(args) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    with open(args[0]) as fa, open(args[1]) as fb:
        a, b = json.load(fa), json.load(fb)
    diffs = compare(a, b, "--notes" in argv)
    for d in diffs:
        print(d)
    n = len(a.get("checks", []))
    print(f"{'IDENTICAL' if not diffs else 'DIFFERENT'}: {args[0]} vs {args[1]} "
          f"({n} checks, {len(diffs)} difference(s))")
    return 0 if not diffs else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
