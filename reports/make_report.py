#!/usr/bin/python3
"""Write the validation report (VALIDATION.md + figures) from verification results.

Usage:
    /usr/bin/python3 reports/make_report.py --results build/verification-results --out reports

Every verification driver writes RESULTS/<dir>/result.json (schema in
verification/README.md). For each result, in sorted order of <dir>, this script

  1. runs verification/<case>/plot.py RESULTS/<dir> with Debian's python, if that
     script exists (a failing plot is reported, not fatal);
  2. copies the figures named in result.json to OUT/figures/<dir>_<name>.png;
  3. writes OUT/VALIDATION.md: header (UTC time, git commit, dirty tree), summary
     table, then per case its checks, metrics, notes and figures.

With --junit (ctest --output-junit), the report also lists every CTest test that did
not pass, so a driver that crashed before writing result.json is still visible.

Exit status: 0 when a report was written, 1 when RESULTS holds no result.json
(a report saying so is still written). Case failures do not change the exit status:
scripts/verify returns ctest's.

Needs only the Python standard library (plot.py scripts use matplotlib + numpy).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import math
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parent.parent
DEFAULT_PYTHON = "/usr/bin/python3" if Path("/usr/bin/python3").exists() else sys.executable
PLOT_TIMEOUT_S = 900
MARK_OK = "✅"
MARK_BAD = "❌"
COMPARATORS = {
    "<=": lambda v, t: v <= t,
    "<": lambda v, t: v < t,
    ">=": lambda v, t: v >= t,
    ">": lambda v, t: v > t,
    "==": lambda v, t: v == t,
}


# --------------------------------------------------------------------------- format
def fmt_value(v) -> str:
    """Numbers with 4 significant digits, everything else as compact text."""
    if v is None:
        return "n/a"
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "NaN"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        if v.is_integer() and abs(v) < 1e7:   # counts stored as JSON doubles
            return str(int(v))
        return f"{v:.4g}"
    if isinstance(v, (list, tuple)):
        if len(v) <= 8:
            return "[" + ", ".join(fmt_value(x) for x in v) + "]"
        nums = [x for x in v if isinstance(x, (int, float)) and not isinstance(x, bool)]
        if len(nums) == len(v):
            return f"[{len(v)} values, {fmt_value(min(nums))} .. {fmt_value(max(nums))}]"
        return f"[{len(v)} items]"
    return str(v)


def cell(v) -> str:
    """Text safe inside a markdown table cell."""
    s = v if isinstance(v, str) else fmt_value(v)
    return s.replace("|", "\\|").replace("\r", "").replace("\n", " ").strip()


def table(header: list[str], rows: list[list[str]]) -> list[str]:
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    out += ["| " + " | ".join(r) + " |" for r in rows]
    return out


def flatten(d, prefix: str = "") -> list[tuple[str, object]]:
    """Nested dicts to dotted keys, in the order the driver wrote them."""
    items: list[tuple[str, object]] = []
    for k, v in d.items():
        key = f"{prefix}.{k}" if prefix else str(k)
        if isinstance(v, dict) and v:
            items += flatten(v, key)
        else:
            items.append((key, v))
    return items


def anchor(name: str) -> str:
    return "case-" + "".join(c if c.isalnum() or c in "-_" else "-" for c in name.lower())


# --------------------------------------------------------------------------- checks
def is_number(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def recompute_passed(check: dict):
    """The check's outcome from value/comparison/threshold, or None if not computable."""
    v, t, cmp = check.get("value"), check.get("threshold"), check.get("comparison")
    if cmp in COMPARATORS and is_number(v) and is_number(t):
        if isinstance(v, float) and math.isnan(v):
            return False
        return COMPARATORS[cmp](v, t)
    if cmp in ("in", "between") and is_number(v) and isinstance(t, list) and len(t) == 2 \
            and all(is_number(x) for x in t):
        return t[0] <= v <= t[1]
    return None


def evaluate_check(check: dict) -> dict:
    """Outcome, expectation and whether they match; flags driver inconsistencies."""
    expected = str(check.get("expected", "pass")).lower()
    recomputed = recompute_passed(check)
    passed = check.get("passed")
    warnings = []
    if not isinstance(passed, bool):
        passed = bool(recomputed) if recomputed is not None else False
        if recomputed is None:
            warnings.append("no outcome recorded")
    elif recomputed is not None and recomputed != passed:
        warnings.append(f"driver says {'pass' if passed else 'fail'} but value {check.get('comparison')} "
                        f"threshold gives {'pass' if recomputed else 'fail'}")
    if expected not in ("pass", "fail"):
        warnings.append(f"unknown expectation '{expected}'")
    matches = (passed and expected == "pass") or (not passed and expected == "fail")
    if warnings:
        matches = False
    if passed:
        outcome = "pass" if expected == "pass" else "unexpected pass"
    else:
        outcome = "expected failure (seed)" if expected == "fail" else "**FAIL**"
    return {"passed": passed, "expected": expected, "matches": matches,
            "outcome": outcome, "warnings": warnings}


def threshold_text(check: dict) -> str:
    cmp, t = check.get("comparison"), check.get("threshold")
    if cmp is None and t is None:
        return ""
    if cmp in ("in", "between") and isinstance(t, list):
        return f"in {fmt_value(t)}"
    return f"{cmp or '?'} {fmt_value(t)}"


# --------------------------------------------------------------------------- cases
def run_plot(source_dir: Path, case_id: str, case_dir: Path, python: str):
    """Run verification/<case>/plot.py; returns None (no script) or (ok, message)."""
    if not case_id or "/" in case_id or case_id in (".", ".."):
        return None
    script = source_dir / "verification" / case_id / "plot.py"
    if not script.is_file():
        return None
    env = dict(os.environ, MPLBACKEND="Agg")
    try:
        proc = subprocess.run([python, str(script), str(case_dir.resolve())], cwd=source_dir, env=env,
                              capture_output=True, text=True, timeout=PLOT_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return (False, f"plot.py timed out after {PLOT_TIMEOUT_S} s")
    except OSError as e:
        return (False, f"plot.py could not be started: {e}")
    if proc.returncode != 0:
        tail = "\n".join((proc.stderr or proc.stdout).strip().splitlines()[-15:])
        return (False, f"plot.py exited with status {proc.returncode}:\n\n```\n{tail}\n```")
    return (True, "")


def load_case(result_path: Path) -> dict:
    """Reads one result.json; unreadable files become an 'error' case."""
    dirname = result_path.parent.name
    try:
        data = json.loads(result_path.read_text(encoding="utf-8"))
        if not isinstance(data, dict):
            raise ValueError("top level is not a JSON object")
    except (OSError, ValueError) as e:
        return {"dir": dirname, "case": dirname, "title": dirname, "error": f"unreadable result.json: {e}",
                "checks": [], "metrics": {}, "figures": [], "notes": ""}
    data["dir"] = dirname
    data.setdefault("case", dirname)
    for key, default in (("checks", []), ("metrics", {}), ("figures", []), ("notes", "")):
        if not isinstance(data.get(key), type(default)):
            data[key] = default
    return data


def summarise(case: dict) -> dict:
    evals = [evaluate_check(c if isinstance(c, dict) else {}) for c in case["checks"]]
    matched = sum(e["matches"] for e in evals)
    computed = "pass" if evals and matched == len(evals) and "error" not in case else "fail"
    driver = str(case.get("status", "")).lower()
    if "error" in case:
        status = "error"
    elif not evals:
        status = "fail (no checks)"
    elif driver and driver != computed:
        status = f"{computed} (driver says {driver})"
    else:
        status = computed
    return {"evals": evals, "matched": matched, "total": len(evals), "status": status,
            "ok": status == "pass"}


# --------------------------------------------------------------------------- git
def git(source_dir: Path, *args: str):
    try:
        p = subprocess.run(["git", "-C", str(source_dir), *args], capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return None
    return p.stdout if p.returncode == 0 else None


def git_state(source_dir: Path, generated: list[Path]) -> tuple[str, str]:
    """(short commit, dirty description); generated report files do not count as dirty."""
    commit = git(source_dir, "rev-parse", "--short", "HEAD")
    if commit is None:
        return "unknown", "unknown (not a git repository)"
    top = Path((git(source_dir, "rev-parse", "--show-toplevel") or str(source_dir)).strip()).resolve()
    ignore = []
    for g in generated:
        try:
            ignore.append(g.resolve().relative_to(top).as_posix())
        except ValueError:
            pass
    status = git(source_dir, "status", "--porcelain", "--untracked-files=all") or ""
    changed = []
    for line in status.splitlines():
        path = line[3:].split(" -> ")[-1].strip('"')
        if any(path == ig or path.startswith(ig.rstrip("/") + "/") for ig in ignore):
            continue
        changed.append(path)
    dirty = f"yes ({len(changed)} uncommitted path(s))" if changed else "no"
    return commit.strip(), dirty


def read_junit(path: Path):
    """[(test name, status)] from ctest's --output-junit file, or an error string."""
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        return f"ctest results not available ({e})"
    tests = []
    for tc in root.iter("testcase"):
        status = tc.get("status", "")
        if tc.find("failure") is not None or tc.find("error") is not None or status == "fail":
            status = "failed"
        elif tc.find("skipped") is not None or status in ("disabled", "notrun", "skipped"):
            status = "not run"
        else:
            status = "passed"
        tests.append((tc.get("name", "?"), status))
    return tests


def junit_lines(junit) -> tuple[str, list[str]]:
    """(header line, section lines) describing the CTest run."""
    if isinstance(junit, str):
        return f"- ctest: {junit}", []
    bad = [(n, st) for n, st in junit if st != "passed"]
    head = f"- ctest: {len(junit) - len(bad)} of {len(junit)} tests passed"
    if not bad:
        return head, []
    section = ["## CTest tests that did not pass", "",
               "A failed test whose case shows all checks as expected crashed or failed after "
               "writing result.json; a failed test with no case below wrote none.", ""]
    section += table(["test", "ctest outcome"], [[cell(n), f"{MARK_BAD} {st}"] for n, st in bad])
    return head, section + [""]


def utc_now() -> str:
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    now = (_dt.datetime.fromtimestamp(int(epoch), _dt.timezone.utc) if epoch
           else _dt.datetime.now(_dt.timezone.utc))
    return now.strftime("%Y-%m-%d %H:%M:%S UTC")


# --------------------------------------------------------------------------- report
def render_case(case: dict, summ: dict, plot_result, figures: list[tuple[str, str | None]]) -> list[str]:
    title = case.get("title") or case["case"]
    lines = [f'<a id="{anchor(case["dir"])}"></a>', "", f"## {case['case']}: {title}", ""]
    meta = [f"seed section {case.get('seed_section', '?')}", f"tier {case.get('tier', '?')}",
            f"status **{summ['status']}**", f"{summ['matched']}/{summ['total']} checks as expected"]
    if case["dir"] != case["case"]:
        meta.append(f"results in `{case['dir']}/`")
    lines += [" · ".join(meta), ""]
    if "error" in case:
        lines += [f"**Error:** {case['error']}", ""]

    if summ["evals"]:
        rows = []
        for check, ev in zip(case["checks"], summ["evals"]):
            check = check if isinstance(check, dict) else {}
            note = check.get("note", "") or ""
            if ev["warnings"]:
                note = (note + "; " if note else "") + "⚠ " + "; ".join(ev["warnings"])
            rows.append([cell(check.get("name", "?")), cell(check.get("value")), cell(threshold_text(check)),
                         cell(ev["expected"]), cell(ev["outcome"]),
                         MARK_OK if ev["matches"] else f"{MARK_BAD} **no**", cell(note)])
        lines += ["### Checks", ""]
        lines += table(["check", "value", "criterion", "expected", "outcome", "as expected", "note"], rows)
        lines.append("")
    else:
        lines += ["No checks recorded: a case must assert numbers, not only finish.", ""]

    metrics = flatten(case["metrics"])
    if metrics:
        lines += ["### Metrics", ""]
        lines += table(["metric", "value"], [[cell(k), cell(v)] for k, v in metrics])
        lines.append("")

    notes = str(case.get("notes") or "").strip()
    if notes:
        lines += ["### Notes", "", notes, ""]

    if plot_result is not None and not plot_result[0]:
        lines += [f"**Plot failed:** {plot_result[1]}", ""]
    if figures:
        lines += ["### Figures", ""]
        for name, rel in figures:
            if rel is None:
                lines += [f"*Figure `{name}` is missing.*", ""]
            else:
                lines += [f"![{case['case']}: {name}]({rel})", ""]
    return lines


def run_time_text(case: dict) -> str:
    """Wall time of the case's runner (result.json `wall_s`), else the sum of its runs'."""
    seconds = case.get("wall_s")
    if not isinstance(seconds, (int, float)):
        runs = [m.get("wall_s") for m in case.get("metrics", {}).values() if isinstance(m, dict)]
        runs = [r for r in runs if isinstance(r, (int, float))]
        seconds = sum(runs) if runs else None
    if seconds is None:
        return "-"
    return f"{seconds:.0f} s" if seconds < 120 else f"{seconds / 60:.1f} min"


def write_report(results: Path, out: Path, source_dir: Path, python: str, junit_path: Path | None = None) -> int:
    out.mkdir(parents=True, exist_ok=True)
    fig_dir = out / "figures"
    report_path = out / "VALIDATION.md"
    commit, dirty = git_state(source_dir, [report_path, fig_dir])

    result_files = sorted(results.glob("*/result.json"), key=lambda p: p.parent.name) if results.is_dir() else []
    header = ["# HFDDA validation report", "",
              f"- generated: {utc_now()}",
              f"- commit: `{commit}`",
              f"- uncommitted changes: {dirty}",
              "- produced by `scripts/verify` (`reports/make_report.py`); "
              "harness described in `verification/README.md`"]
    ctest_section: list[str] = []
    if junit_path is not None:
        ctest_head, ctest_section = junit_lines(read_junit(junit_path))
        header.append(ctest_head)
    header.append("")

    if not result_files:
        lines = header + [f"**No verification results found** in `{results}`: "
                          "no verification test wrote a result.json.", ""] + ctest_section
        report_path.write_text("\n".join(lines), encoding="utf-8")
        print(f"make_report: no results in {results}; wrote {report_path}", file=sys.stderr)
        return 1

    fig_dir.mkdir(parents=True, exist_ok=True)
    produced: set[str] = set()
    sections, summary_rows, n_ok = [], [], 0
    for path in result_files:
        case = load_case(path)
        case_dir = path.parent
        plot_result = None if "error" in case else run_plot(source_dir, str(case["case"]), case_dir, python)
        figures = []
        for name in case["figures"]:
            name = str(name)
            src = case_dir / name
            if Path(name).is_absolute() or ".." in Path(name).parts or not src.is_file():
                figures.append((name, None))
                continue
            dest_name = f"{case['dir']}_{Path(name).stem}{Path(name).suffix or '.png'}"
            shutil.copyfile(src, fig_dir / dest_name)
            produced.add(dest_name)
            figures.append((name, f"figures/{dest_name}"))
        summ = summarise(case)
        n_ok += summ["ok"]
        status = summ["status"] if summ["ok"] else f"**{summ['status']}**"
        n_fig = sum(rel is not None for _, rel in figures)
        fig_text = f"{n_fig}/{len(figures)}" if figures else "none"
        if n_fig < len(figures) or (plot_result is not None and not plot_result[0]):
            fig_text += " ⚠ plot failed" if plot_result is not None and not plot_result[0] else " ⚠"
        summary_rows.append([f"[{cell(str(case['case']))}](#{anchor(case['dir'])})",
                             cell(str(case.get("seed_section", ""))), cell(str(case.get("tier", ""))),
                             f"{MARK_OK if summ['ok'] else MARK_BAD} {status}",
                             f"{summ['matched']}/{summ['total']}", run_time_text(case), fig_text])
        sections += render_case(case, summ, plot_result, figures)

    # Figures of cases no longer in the results would contradict the report: drop them.
    for stale in sorted(fig_dir.glob("*.png")):
        if stale.name not in produced:
            stale.unlink()

    lines = header + ["## Summary", "",
                      f"{n_ok} of {len(result_files)} case results pass. A check whose seed result is a "
                      "known failure (expected `fail`) counts as matched when it fails.", ""]
    lines += table(["case", "seed section", "tier", "status", "checks as expected", "run time", "figures"],
                   summary_rows)
    lines.append("")
    lines += ctest_section
    lines += sections
    report_path.write_text("\n".join(lines).rstrip("\n") + "\n", encoding="utf-8")
    print(f"make_report: {n_ok}/{len(result_files)} case results pass; wrote {report_path}")
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--results", type=Path, required=True, help="directory holding <case>/result.json")
    ap.add_argument("--out", type=Path, required=True, help="output directory (VALIDATION.md, figures/)")
    ap.add_argument("--source-dir", type=Path, default=REPO_ROOT,
                    help="repository root holding verification/<case>/plot.py (default: %(default)s)")
    ap.add_argument("--python", default=DEFAULT_PYTHON, help="interpreter for plot.py (default: %(default)s)")
    ap.add_argument("--junit", type=Path, help="ctest --output-junit file of the same run (optional)")
    args = ap.parse_args(argv)
    return write_report(args.results, args.out, args.source_dir, args.python, args.junit)


if __name__ == "__main__":
    sys.exit(main())
