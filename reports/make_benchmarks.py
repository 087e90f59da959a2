#!/usr/bin/python3
"""Write BENCHMARKS.md from Google Benchmark JSON files.

Usage:
    /usr/bin/python3 reports/make_benchmarks.py --results build/benchmark-results --out reports/BENCHMARKS.md

One table per JSON file (sorted by file name; benchmarks in run order): name, real
and CPU time in ms, iterations, every user counter (union over the file, blank when
a benchmark lacks it) and, when any benchmark has a `target_s` counter, whether its
real time in seconds meets that target. With repetitions, a benchmark's row is its
median aggregate (time and counters), with the number of repetitions.

Benchmarks with a `threads:N` argument also appear in a table "threads 1 vs 2": per
step, wall and process CPU time (counters step_s and cpu_s, else real and CPU time)
at each thread count, the speed-up (wall at 1 over wall at N) and the CPU cost (CPU at
N over CPU at 1). --comparison adds a Markdown section (benchmarks/compare_baseline.py)
after the header.

Exit status: 0 when the report was written from readable files; 1 when there were
no JSON files or one could not be read (the report is still written).

Standard library only.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parent.parent
TO_MS = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}
STANDARD_KEYS = {
    "name", "family_index", "per_family_instance_index", "run_name", "run_type", "repetitions",
    "repetition_index", "threads", "iterations", "real_time", "cpu_time", "time_unit",
    "aggregate_name", "aggregate_unit", "error_occurred", "error_message", "skipped", "skip_message",
    "label", "cpu_coefficient", "real_coefficient", "big_o", "rms",
}
STANDARD_CONTEXT = {
    "date", "host_name", "executable", "num_cpus", "mhz_per_cpu", "cpu_scaling_enabled", "caches",
    "load_avg", "library_build_type", "library_version", "json_schema_version",
}


def fmt(v) -> str:
    if v is None:
        return ""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v) or math.isinf(v):
            return str(v)
        if v.is_integer() and abs(v) < 1e7:   # counts stored as JSON doubles
            return str(int(v))
        return f"{v:.4g}"
    return str(v).replace("|", "\\|").replace("\n", " ")


def is_number(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def time_ms(b: dict, key: str) -> str:
    """A time column in ms; percentages (e.g. the cv aggregate) stay as they are."""
    v = b.get(key)
    if not is_number(v):
        return ""
    if b.get("aggregate_unit") == "percentage":
        return f"{100.0 * v:.3g} %"
    factor = TO_MS.get(b.get("time_unit", "ns"))
    return "" if factor is None else fmt(float(v) * factor)


def meets_target(b: dict) -> str:
    target, real = b.get("target_s"), b.get("real_time")
    if not is_number(target) or not is_number(real) or b.get("aggregate_unit") == "percentage":
        return ""
    if b.get("run_type") == "aggregate" and b.get("aggregate_name") not in ("mean", "median"):
        return ""
    factor = TO_MS.get(b.get("time_unit", "ns"))
    if factor is None:
        return ""
    seconds = float(real) * factor * 1e-3
    return "yes ✅" if seconds <= target else f"no ❌ ({seconds / target:.2f}x)"


def failed(b: dict) -> str | None:
    if b.get("error_occurred") or b.get("skipped"):
        return str(b.get("error_message") or b.get("skip_message") or "error")
    return None


def select_rows(benches: list[dict]) -> list[dict]:
    """With repetitions, each benchmark's median aggregate; errors and single runs as they are.
    In registration order, whatever order random interleaving ran them in."""
    aggregated = {b.get("run_name") for b in benches if b.get("run_type") == "aggregate"}
    rows = [b for b in benches
            if failed(b) is not None
            or (b.get("run_type") == "aggregate" and b.get("aggregate_name") == "median")
            or (b.get("run_type") != "aggregate" and b.get("run_name") not in aggregated)]
    return sorted(rows, key=lambda b: (b.get("family_index", 0), b.get("per_family_instance_index", 0)))


THREADS = re.compile(r"/threads:(\d+)")


def threads_table(rows: list[dict]) -> list[str]:
    """Per benchmark size, wall and CPU time per step at each thread count."""
    groups: dict[str, dict[int, dict]] = {}
    for b in rows:
        name = str(b.get("run_name", b.get("name", "")))
        m = THREADS.search(name)
        if m and failed(b) is None:
            base = re.sub(r"/(process_time|real_time|iterations:\d+|repeats:\d+)", "", THREADS.sub("", name))
            groups.setdefault(base, {})[int(m.group(1))] = b
    groups = {k: v for k, v in groups.items() if 1 in v and len(v) > 1}
    if not groups:
        return []

    def per_step(b: dict, counter: str, key: str) -> float | None:
        if is_number(b.get(counter)):
            return 1e3 * float(b[counter])
        factor = TO_MS.get(b.get("time_unit", "ns"))
        return float(b[key]) * factor if is_number(b.get(key)) and factor else None

    lines = ["## Threads: 1 vs 2", "",
             "Per step: wall time, and CPU time of the whole process (user + system, all threads). "
             "Speed-up = wall at 1 thread / wall at N; CPU cost = CPU at N / CPU at 1; sys/user = "
             "system over user CPU time (idle threads spinning in futex and sched_yield). What else runs on "
             "the machine changes the 2-thread rows most: see each binary's load average below.", "",
             "| benchmark | blocks | threads | wall per step (ms) | CPU per step (ms) | speed-up | CPU cost "
             "| sys/user |", "|---|---|---|---|---|---|---|---|"]
    for base, by_threads in groups.items():
        wall1 = per_step(by_threads[1], "step_s", "real_time")
        cpu1 = per_step(by_threads[1], "cpu_s", "cpu_time")
        for n in sorted(by_threads):
            b = by_threads[n]
            wall, cpu = per_step(b, "step_s", "real_time"), per_step(b, "cpu_s", "cpu_time")
            speedup = f"{wall1 / wall:.2f}" if wall and wall1 and n != 1 else ""
            cost = f"{cpu / cpu1:.2f}" if cpu and cpu1 and n != 1 else ""
            lines.append(f"| {fmt(base)} | {fmt(b.get('blocks'))} | {n} | {fmt(wall)} | {fmt(cpu)} | {speedup} "
                         f"| {cost} | {fmt(b.get('sys_over_user'))} |")
    return lines + [""]


def read_results(path: Path) -> tuple[dict, list[dict]]:
    data = json.loads(path.read_text(encoding="utf-8"))
    ctx = data.get("context", {}) or {}
    benches = data.get("benchmarks", []) or []
    if not isinstance(ctx, dict) or not isinstance(benches, list):
        raise ValueError("unexpected layout (need 'context' object and 'benchmarks' list)")
    return ctx, [b for b in benches if isinstance(b, dict)]


def render_file(path: Path) -> tuple[list[str], bool]:
    lines = [f"## {path.stem}", ""]
    try:
        ctx, benches = read_results(path)
    except (OSError, ValueError, AttributeError) as e:
        return lines + [f"**Unreadable:** `{path.name}`: {e}", ""], False

    info = [f"run {ctx.get('date', '?')}",
            f"host {ctx.get('host_name', '?')}: {ctx.get('num_cpus', '?')} CPUs at {ctx.get('mhz_per_cpu', '?')} MHz",
            f"benchmark library build type: {ctx.get('library_build_type', '?')}"]
    if ctx.get("cpu_scaling_enabled"):
        info.append("⚠ CPU frequency scaling enabled (timings are noisier)")
    if isinstance(ctx.get("load_avg"), list) and ctx["load_avg"]:
        info.append("load avg " + ", ".join(fmt(x) for x in ctx["load_avg"]))
    extra = [f"{k}: {fmt(v)}" for k, v in ctx.items()
             if k not in STANDARD_CONTEXT and not isinstance(v, (dict, list))]
    lines += ["- " + "; ".join(info)]
    if extra:
        lines += ["- " + "; ".join(extra)]
    lines.append("")

    if not benches:
        return lines + ["No benchmarks in this file.", ""], True
    benches = select_rows(benches)
    reps = max((int(b["repetitions"]) for b in benches if is_number(b.get("repetitions"))), default=1)
    if reps > 1:
        lines[-1:] = [f"- rows with repetitions: median of up to {reps} repetitions (time and counters)", ""]

    counters: list[str] = []
    for b in benches:
        for k, v in b.items():
            if k not in STANDARD_KEYS and k not in counters and not isinstance(v, (dict, list)):
                counters.append(k)
    has_label = any(b.get("label") for b in benches)
    has_target = "target_s" in counters

    header = ["benchmark", "real time (ms)", "cpu time (ms)", "iterations"]
    header += ["label"] if has_label else []
    header += counters + (["meets target"] if has_target else [])
    rows = []
    for b in benches:
        err = failed(b)
        name = fmt(b.get("name", "?"))
        if err is not None:
            row = [name, f"error: {fmt(err)}", "", fmt(b.get("iterations"))]
        elif "big_o" in b or "rms" in b:
            coeff = b.get("real_coefficient", b.get("rms"))
            row = [name, f"{fmt(coeff)} {fmt(b.get('big_o', 'rms'))}", "", ""]
        else:
            row = [name, time_ms(b, "real_time"), time_ms(b, "cpu_time"), fmt(b.get("iterations"))]
        row += [fmt(b.get("label"))] if has_label else []
        row += [fmt(b.get(c)) for c in counters]
        row += [meets_target(b) if err is None else ""] if has_target else []
        rows.append(row)
    lines.append("| " + " | ".join(header) + " |")
    lines.append("|" + "|".join("---" for _ in header) + "|")
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    lines.append("")
    return lines, True


def git_commit() -> str:
    try:
        p = subprocess.run(["git", "-C", str(REPO_ROOT), "rev-parse", "--short", "HEAD"],
                           capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return "unknown"
    return p.stdout.strip() if p.returncode == 0 else "unknown"


def utc_now() -> str:
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    now = (_dt.datetime.fromtimestamp(int(epoch), _dt.timezone.utc) if epoch
           else _dt.datetime.now(_dt.timezone.utc))
    return now.strftime("%Y-%m-%d %H:%M:%S UTC")


def write_report(results: Path, out: Path, comparison: Path | None = None) -> int:
    files = sorted(results.glob("*.json")) if results.is_dir() else []
    lines = ["# HFDDA benchmarks", "",
             f"- generated: {utc_now()}",
             f"- commit: `{git_commit()}`",
             "- produced by `scripts/bench` (`reports/make_benchmarks.py`); times are wall-clock (real) "
             "and CPU time per iteration, converted to ms", ""]
    ok = bool(files)
    if not files:
        lines += [f"**No benchmark results found** in `{results}`.", ""]
    if comparison is not None:
        try:
            lines += [comparison.read_text(encoding="utf-8").rstrip("\n"), ""]
        except OSError as e:
            lines += [f"**Comparison unreadable:** {e}", ""]
            ok = False
    rows = []
    for f in files:
        try:
            rows += select_rows(read_results(f)[1])
        except (OSError, ValueError, AttributeError):
            pass  # reported by render_file below
    lines += threads_table(rows)
    for f in files:
        section, readable = render_file(f)
        ok &= readable
        lines += section
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text("\n".join(lines).rstrip("\n") + "\n", encoding="utf-8")
    print(f"make_benchmarks: {len(files)} result file(s); wrote {out}", file=sys.stdout if ok else sys.stderr)
    return 0 if ok else 1


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--results", type=Path, required=True, help="directory of Google Benchmark JSON files")
    ap.add_argument("--out", type=Path, required=True, help="markdown file to write")
    ap.add_argument("--comparison", type=Path, help="Markdown section to include (baseline comparison)")
    args = ap.parse_args(argv)
    return write_report(args.results, args.out, args.comparison)


if __name__ == "__main__":
    sys.exit(main())
