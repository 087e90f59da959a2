#!/usr/bin/python3
"""Write the validation report (VALIDATION.md + figures) from verification results.

Usage:
    /usr/bin/python3 reports/make_report.py --results build/verification-results --out reports \
        [--junit FILE] [--readme README.md]

Every verification driver writes RESULTS/<dir>/result.json (schema in
verification/README.md). For each result, in sorted order of <dir>, this script

  1. runs verification/<case>/plot.py RESULTS/<dir> with Debian's python, if that
     script exists (a failing plot is reported, not fatal);
  2. copies the figures named in result.json to OUT/figures/<dir>_<name>.png;
  3. writes OUT/VALIDATION.md: header (UTC time, git commit, whether the working tree
     was clean), summary table, then per case its checks, metrics, notes and figures.
     Gating checks (a miss fails the runner and so CTest) are counted apart from the
     checks that are only reported.

With --junit (ctest --output-junit), the report also lists every CTest test that did
not pass, so a driver that crashed before writing result.json is still visible.

With --readme, the text between the README's markers
    <!-- verified-summary:begin --> and <!-- verified-summary:end -->
is rewritten from the full-tier results: one line per case (title, seed section,
gating and reported-only counts, the first miss). The README is left alone when the
results are partial: a case of verification/ (a folder with study.yaml) without a
full-tier result, e.g. after `scripts/verify --quick` or `-R griffith`.

Exit status: 0 when a report was written, 1 when RESULTS holds no result.json
(a report saying so is still written) or the README's markers are missing or
malformed. Case failures do not change the exit status: scripts/verify returns ctest's.

Needs only the Python standard library (plot.py scripts use matplotlib + numpy).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import math
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path
from source_state import Provenance, git_state, kernels_line, split_readme, update_readme

REPO_ROOT = Path(__file__).resolve().parent.parent
DEFAULT_PYTHON = "/usr/bin/python3" if Path("/usr/bin/python3").exists() else sys.executable
PLOT_TIMEOUT_S = 900
MARK_OK = "✅"
MARK_BAD = "❌"
MARK_WARN = "⚠"
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
    """Outcome, expectation, gating and whether they match; flags driver inconsistencies."""
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
    # The harness decides whether an outcome is the expected one (an expected failure
    # must be a completed run with a finite value, or a stop with the named error); a
    # miss without a value is never an expected failure here either.
    harness_says = check.get("as_expected")
    if isinstance(harness_says, bool):
        matches = matches and harness_says
    elif expected == "fail" and not is_number(check.get("value")):
        matches = False
    if warnings:
        matches = False
    # The harness always writes `gating`; without it the check is counted as gating,
    # so a result of an older or foreign driver cannot hide a miss from the gating count.
    gating = check.get("gating")
    gating_recorded = isinstance(gating, bool)
    gating = gating if gating_recorded else True
    if passed:
        outcome = "pass" if expected == "pass" else "unexpected pass"
    else:
        outcome = ("expected failure (seed)" if matches else "**FAIL** (no value or no completed run)") \
            if expected == "fail" else "**FAIL**"
    return {"passed": passed, "expected": expected, "matches": matches, "gating": gating,
            "gating_recorded": gating_recorded, "outcome": outcome, "warnings": warnings}


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
    """Per case: gating and reported-only checks counted apart, and the case's state.

    `ok` is the runner's verdict recomputed: every gating check matches its expectation
    (what CTest sees). `all_match` also needs every reported-only check to match (what
    the driver writes as `status`)."""
    evals = [evaluate_check(c if isinstance(c, dict) else {}) for c in case["checks"]]
    gating = [e for e in evals if e["gating"]]
    reported = [e for e in evals if not e["gating"]]
    counts = {
        "gating_total": len(gating), "gating_matched": sum(e["matches"] for e in gating),
        "gating_expected_fail": sum(e["expected"] == "fail" for e in gating),
        "reported_total": len(reported), "reported_matched": sum(e["matches"] for e in reported),
        "reported_expected_fail": sum(e["expected"] == "fail" for e in reported),
    }
    all_match = bool(evals) and all(e["matches"] for e in evals) and "error" not in case
    driver = str(case.get("status", "")).lower()
    driver_note = ""
    if driver and "error" not in case and evals and driver != ("pass" if all_match else "fail"):
        driver_note = f"driver says {driver}"
    if "error" in case:
        state = "error"
    elif not evals:
        state = "no checks"
    elif counts["gating_matched"] < counts["gating_total"]:
        state = "gating miss"
    elif counts["reported_matched"] < counts["reported_total"]:
        state = "reported-only miss"
    else:
        state = "pass"
    ok = state in ("pass", "reported-only miss") and not driver_note
    return {"evals": evals, "matched": sum(e["matches"] for e in evals), "total": len(evals),
            "state": state, "ok": ok, "all_match": all_match, "driver_note": driver_note, **counts}


def expected_fail_text(n: int) -> str:
    return f"{n} expected failure{'' if n == 1 else 's'}"


def gating_text(summ: dict, marks: bool = True) -> str:
    """Summary cell for the gating checks, e.g. '✅ 12/12 as expected (2 expected failures)'."""
    if summ["state"] == "error":
        return f"{MARK_BAD} **error**" if marks else "error"
    if summ["state"] == "no checks":
        return f"{MARK_BAD} **no checks**" if marks else "no checks"
    n, m = summ["gating_total"], summ["gating_matched"]
    if n == 0:
        text = "none (nothing gates)"
    else:
        text = f"{m}/{n} as expected"
        if summ["gating_expected_fail"]:
            text += f" ({expected_fail_text(summ['gating_expected_fail'])})"
    if summ["driver_note"]:
        text += f"; {summ['driver_note']}"
    if not marks:
        return text
    return f"{MARK_OK} {text}" if summ["ok"] else f"{MARK_BAD} **{text}**"


def reported_text(summ: dict, marks: bool = True) -> str:
    """Summary cell for the checks that are only reported, e.g. '⚠ 3/5 as expected'."""
    n, m = summ["reported_total"], summ["reported_matched"]
    if n == 0:
        return "none"
    text = f"{m}/{n} as expected"
    if summ["reported_expected_fail"]:
        text += f" ({expected_fail_text(summ['reported_expected_fail'])})"
    if not marks:
        return text
    return f"{MARK_OK if m == n else MARK_WARN} {text}"


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
            f"gating checks: {gating_text(summ)}", f"reported only: {reported_text(summ)}"]
    if case["dir"] != case["case"]:
        meta.append(f"results in `{case['dir']}/`")
    lines += [" · ".join(meta), ""]
    if "error" in case:
        lines += [f"**Error:** {case['error']}", ""]

    # Tables the case made for the reader (e.g. outcomes beside the experiment's and the seed's).
    for t in case.get("tables") or []:
        if not isinstance(t, dict) or not isinstance(t.get("header"), list) or not isinstance(t.get("rows"), list):
            lines += ["*A table in result.json is malformed (needs title, header, rows) and is not shown.*", ""]
            continue
        lines += [f"### {t.get('title', 'Table')}", ""]
        lines += table([cell(h) for h in t["header"]],
                       [[cell(c) for c in row] for row in t["rows"] if isinstance(row, list)])
        lines.append("")

    if summ["evals"]:
        rows = []
        for check, ev in zip(case["checks"], summ["evals"]):
            check = check if isinstance(check, dict) else {}
            note = check.get("note", "") or ""
            warnings = list(ev["warnings"])
            if not ev["gating_recorded"]:
                warnings.append("no gating flag recorded: counted as gating")
            if warnings:
                note = (note + "; " if note else "") + "⚠ " + "; ".join(warnings)
            if ev["matches"]:
                as_expected = MARK_OK
            elif ev["gating"]:
                as_expected = f"{MARK_BAD} **no**"
            else:
                as_expected = f"{MARK_WARN} no (reported only)"
            rows.append([cell(check.get("name", "?")), "**yes**" if ev["gating"] else "no",
                         cell(check.get("value")), cell(threshold_text(check)), cell(ev["expected"]),
                         cell(ev["outcome"]), as_expected, cell(note)])
        lines += ["### Checks", "",
                  "A gating check that misses its expectation fails the runner and so CTest; the others "
                  "are reported only. Expected `fail`: the seed itself reports the failure.", ""]
        lines += table(["check", "gating", "value", "criterion", "expected", "outcome", "as expected", "note"],
                       rows)
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


# --------------------------------------------------------------------------- README
def section_key(case: dict) -> tuple:
    """Sort key: seed section as numbers ('3.4, 3.5' -> (3, 4)), then the case name."""
    first = re.findall(r"\d+(?:\.\d+)*", str(case.get("seed_section", "")))
    nums = tuple(int(x) for x in first[0].split(".")) if first else (10**6,)
    return nums, str(case["case"])


def chapters_text(cases: list[dict]) -> str:
    chapters = sorted({int(m) for c in cases for m in re.findall(r"(\d+)\.\d+", str(c.get("seed_section", "")))})
    if not chapters:
        return ""
    if len(chapters) > 1 and chapters == list(range(chapters[0], chapters[-1] + 1)):
        return f"seed chapters {chapters[0]}-{chapters[-1]}"
    return ("seed chapter " if len(chapters) == 1 else "seed chapters ") + ", ".join(map(str, chapters))


def first_miss(case: dict, summ: dict) -> str:
    """The first gating miss, else the first reported-only one, as README text."""
    pairs = [(c if isinstance(c, dict) else {}, e) for c, e in zip(case["checks"], summ["evals"])]
    misses = [(c, e) for c, e in pairs if not e["matches"] and e["gating"]] + \
             [(c, e) for c, e in pairs if not e["matches"] and not e["gating"]]
    if not misses:
        return ""
    check, ev = misses[0]
    name = str(check.get("name", "?")).replace("`", "'").replace("\n", " ")
    value = check.get("value")
    got = f"is {fmt_value(value)}" if value is not None else "has no value"
    want = threshold_text(check)
    text = (f"first miss ({'gating' if ev['gating'] else 'reported only'}): `{name}` {got}"
            f"{', criterion ' + want if want else ''}, expected {ev['expected']}")
    if len(misses) > 1:
        more = len(misses) - 1
        text += f" ({more} more miss{'' if more == 1 else 'es'})"
    return text


def readme_case_line(case: dict, summ: dict, readme_dir: Path, source_dir: Path) -> str:
    title = str(case.get("title") or case["case"]).replace("\n", " ")
    parts = [f"gating {gating_text(summ, marks=False)}", f"reported only {reported_text(summ, marks=False)}"]
    miss = first_miss(case, summ)
    if miss:
        parts.append(miss)
    line = f"- {title} ({case.get('seed_section', '?')}): " + "; ".join(parts)
    case_readme = source_dir / "verification" / str(case["case"]) / "README.md"
    if case_readme.is_file():
        link = Path(os.path.relpath(case_readme, readme_dir)).as_posix()
        line += f" ([`{link}`]({link}))"
    return line + "."


def readme_section(full: list[tuple[dict, dict]], prov: Provenance, date: str, readme_dir: Path,
                   source_dir: Path, report_path: Path) -> str:
    """The text between the README markers: where the numbers come from, one line per case."""
    report = Path(os.path.relpath(report_path, readme_dir)).as_posix()
    guide = Path(os.path.relpath(source_dir / "verification" / "README.md", readme_dir)).as_posix()
    full = sorted(full, key=lambda cs: section_key(cs[0]))
    scope = chapters_text([c for c, _ in full])
    n_ok = sum(s["ok"] for _, s in full)
    lines = ["<!-- Written by reports/make_report.py from the full verification tier: "
             "change the generator or the cases, not this text. -->",
             f"Verified so far{' (' + scope + ')' if scope else ''}: the full verification tier at "
             f"{prov.short()}, {date}. Every check is in [`{report}`]({report}); cases, tiers and "
             f"times in [`{guide}`]({guide}). A gating check that misses fails CI; the others are "
             f"reported only. {n_ok} of {len(full)} cases meet every gating check."]
    lines += [readme_case_line(c, s, readme_dir, source_dir) for c, s in full]
    return "\n".join(lines) + "\n"


def expected_cases(source_dir: Path) -> list[str]:
    """Cases of verification/ (folders with a study.yaml)."""
    vdir = source_dir / "verification"
    if not vdir.is_dir():
        return []
    return sorted(d.name for d in vdir.iterdir() if (d / "study.yaml").is_file())


def full_tier_gaps(cases: list[tuple[dict, dict]], source_dir: Path) -> list[str]:
    """Cases without a usable full-tier result: those of verification/, or, when the
    source has none, those that have a result of any tier."""
    full = {str(c["case"]) for c, _ in cases if c.get("tier") == "full" and "error" not in c}
    known = expected_cases(source_dir)
    if not known:
        known = sorted({str(c["case"]) for c, _ in cases if "error" not in c} |
                       {c["dir"].removesuffix("-quick") for c, _ in cases if "error" in c})
    return [k for k in known if k not in full]


# --------------------------------------------------------------------------- report
def write_report(results: Path, out: Path, source_dir: Path, python: str, junit_path: Path | None = None,
                 readme: Path | None = None) -> int:
    out.mkdir(parents=True, exist_ok=True)
    fig_dir = out / "figures"
    report_path = out / "VALIDATION.md"
    # The README's generated section is output too, also when this run does not rewrite it.
    prov = git_state(source_dir, [report_path, fig_dir, results], readme or source_dir / "README.md")
    generated_at = utc_now()

    result_files = sorted(results.glob("*/result.json"), key=lambda p: p.parent.name) if results.is_dir() else []
    header = ["# HFDDA validation report", "",
              f"- generated: {generated_at}",
              f"- commit: {prov.commit_line()}",
              "- produced by `scripts/verify` (`reports/make_report.py`); "
              "harness described in `verification/README.md`"]
    ctest_section: list[str] = []
    if junit_path is not None:
        ctest_head, ctest_section = junit_lines(read_junit(junit_path))
        header.append(ctest_head)

    readme_error = ""
    if readme is not None:
        try:
            split_readme(readme.read_text(encoding="utf-8"), str(readme))
        except (OSError, UnicodeDecodeError, ValueError) as e:
            readme_error = str(e)

    if not result_files:
        if readme is not None:
            header.append(f"- README summary: not updated ({readme_error or 'no results'})")
        lines = header + ["", f"**No verification results found** in `{results}`: "
                          "no verification test wrote a result.json.", ""] + ctest_section
        report_path.write_text("\n".join(lines), encoding="utf-8")
        print(f"make_report: no results in {results}; wrote {report_path}", file=sys.stderr)
        if readme_error:
            print(f"make_report: {readme_error}", file=sys.stderr)
        return 1

    cases = [load_case(path) for path in result_files]
    header.insert(5, kernels_line(cases))  # after "produced by"
    fig_dir.mkdir(parents=True, exist_ok=True)
    produced: set[str] = set()
    sections, summary_rows, summarised = [], [], []
    for path, case in zip(result_files, cases):
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
        summarised.append((case, summ))
        n_fig = sum(rel is not None for _, rel in figures)
        fig_text = f"{n_fig}/{len(figures)}" if figures else "none"
        if n_fig < len(figures) or (plot_result is not None and not plot_result[0]):
            fig_text += " ⚠ plot failed" if plot_result is not None and not plot_result[0] else " ⚠"
        summary_rows.append([f"[{cell(str(case['case']))}](#{anchor(case['dir'])})",
                             cell(str(case.get("seed_section", ""))), cell(str(case.get("tier", ""))),
                             cell(gating_text(summ)), cell(reported_text(summ)),
                             run_time_text(case), fig_text])
        sections += render_case(case, summ, plot_result, figures)

    # Figures of cases no longer in the results would contradict the report: drop them,
    # but not those of the benchmark report beside it (BENCHMARKS.md, make_benchmarks.py).
    benchmarks = out / "BENCHMARKS.md"
    benchmark_figures = set(re.findall(r"figures/([^)\s]+\.png)", benchmarks.read_text())) if benchmarks.is_file() else set()
    for stale in sorted(fig_dir.glob("*.png")):
        if stale.name not in produced and stale.name not in benchmark_figures:
            stale.unlink()

    readme_note = ""
    if readme is not None:
        gaps = full_tier_gaps(summarised, source_dir)
        if readme_error:
            readme_note = f"not updated ({readme_error})"
        elif gaps:
            readme_note = ("not updated: partial results, no full-tier result for " +
                           ", ".join(f"`{g}`" for g in gaps))
        else:
            full = [(c, s) for c, s in summarised if c.get("tier") == "full"]
            section = readme_section(full, prov, generated_at[:10], readme.resolve().parent,
                                     source_dir.resolve(), report_path.resolve())
            try:
                changed = update_readme(readme, section)
                readme_note = f"`{readme.name}` section regenerated from the full-tier results" + \
                    ("" if changed else " (unchanged)")
            except (OSError, ValueError) as e:
                readme_error = str(e)
                readme_note = f"not updated ({readme_error})"
        header.append(f"- README summary: {readme_note}")
    header.append("")

    n = len(summarised)
    n_ok = sum(s["ok"] for _, s in summarised)
    n_all = sum(s["all_match"] for _, s in summarised)
    lines = header + ["## Summary", "",
                      f"{n_ok} of {n} case results meet every gating check (a gating miss fails CTest); "
                      f"{n_all} of {n} have every check as expected, the reported-only ones included. "
                      "A check whose seed result is a known failure (expected `fail`) counts as expected "
                      "when it fails.", ""]
    lines += table(["case", "seed section", "tier", "gating checks", "reported only", "run time", "figures"],
                   summary_rows)
    lines.append("")
    lines += ctest_section
    lines += sections
    report_path.write_text("\n".join(lines).rstrip("\n") + "\n", encoding="utf-8")
    print(f"make_report: {n_ok}/{n} case results meet every gating check; wrote {report_path}")
    if readme is not None:
        print(f"make_report: README summary {readme_note}", file=sys.stderr if readme_error else sys.stdout)
    return 1 if readme_error else 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--results", type=Path, required=True, help="directory holding <case>/result.json")
    ap.add_argument("--out", type=Path, required=True, help="output directory (VALIDATION.md, figures/)")
    ap.add_argument("--source-dir", type=Path, default=REPO_ROOT,
                    help="repository root holding verification/<case>/plot.py (default: %(default)s)")
    ap.add_argument("--python", default=DEFAULT_PYTHON, help="interpreter for plot.py (default: %(default)s)")
    ap.add_argument("--junit", type=Path, help="ctest --output-junit file of the same run (optional)")
    ap.add_argument("--readme", type=Path,
                    help="README whose verified-summary section is rewritten from full-tier results (optional)")
    args = ap.parse_args(argv)
    return write_report(args.results, args.out, args.source_dir, args.python, args.junit, args.readme)


if __name__ == "__main__":
    sys.exit(main())
