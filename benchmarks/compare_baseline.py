#!/usr/bin/python3
"""Compare a scripts/bench run with the stored baseline, or store the run as the baseline.

Usage:
    /usr/bin/python3 benchmarks/compare_baseline.py --results build/benchmark-results \\
        --baseline benchmarks/baseline.json [--markdown OUT.md]
    /usr/bin/python3 benchmarks/compare_baseline.py --results build/benchmark-results \\
        --save benchmarks/baseline.json

A run is a directory of Google Benchmark JSON files, one per binary. Per benchmark it
keeps, for the CPU time of the process (all threads) and the wall (real) time, the
median over repetitions and a robust relative noise: 1.4826 x the median absolute
deviation, over the median.

Normalised times: each benchmark also times a fixed piece of work that touches none of
HFDDA's code next to every repetition (counters calibration_cpu_ms and
calibration_real_ms, benchmarks/bench_support.hpp). A busy spell of the shared machine
that lasts longer than a repetition slows both, so the per-repetition ratio of the two
holds still where either time moves. Its median and noise are the normalised time and
its noise. (Dividing by BM_Calibration, timed once per binary, was tried first: its
own moment of the run is as noisy as any other, and between two runs the median ratio
strayed 15 % (CPU) and 30 % (wall) from 1, against 3.5 % with the adjacent work.)

The verdict is on the ratio now / baseline of normalised CPU times (--metric real for
wall times): "slower" above the limit 1 + max(K x noise, FLOOR), "faster" below its
inverse, where noise is the larger of the baseline's and this run's. CPU time, because
a busy neighbour stretches wall time more: two runs of bench_dda at a load of 2.5-3.5
on 2 cores had median limits of 1.15 in CPU time and 1.37 in wall time, and the same
3.5 % median departure from 1. Without the calibration counters, the same host
compares absolute times; another host (CPU model or count differs) compares times
divided by BM_Calibration's median, with a warning, and nothing without it.

Exit status: 0 when nothing is slower; 1 when a benchmark is flagged slower or failed;
2 when the inputs cannot be read. Without a baseline file it warns and exits 0.

Standard library only.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import math
import os
import re
import statistics
import subprocess
import sys
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parent.parent
CALIBRATION = "BM_Calibration"
METRICS = ("real", "cpu")
TO_MS = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}
# Run settings, not identity: the same benchmark keeps its key when they change.
NAME_NOISE = re.compile(r"/(repeats|iterations|min_time):[^/]+|/process_time|/real_time|/manual_time")
SCHEMA = 1


def bench_key(binary: str, run_name: str) -> str:
    return f"{binary}:{NAME_NOISE.sub('', run_name)}"


def robust_noise(values: list[float]) -> float | None:
    """1.4826 MAD / median (the standard deviation for normal noise), None below 2 values."""
    if len(values) < 2:
        return None
    med = statistics.median(values)
    if med <= 0:
        return None
    return 1.4826 * statistics.median(abs(v - med) for v in values) / med


def summarise(entries: list[dict]) -> dict:
    """Median and noise of one benchmark's repetitions (or of its median aggregate)."""
    errors = [e for e in entries if e.get("error_occurred") or e.get("skipped")]
    if errors:
        return {"error": str(errors[0].get("error_message") or errors[0].get("skip_message") or "error")}
    reps = [e for e in entries if e.get("run_type", "iteration") == "iteration"]
    out: dict = {}
    if reps:
        out["repetitions"] = len(reps)
        for m in METRICS:
            values = [float(e[f"{m}_time"]) * TO_MS[e.get("time_unit", "ns")] for e in reps]
            out[m] = {"median_ms": statistics.median(values), "noise": robust_noise(values)}
            # The calibration timed next to each repetition (counter calibration_<metric>_ms).
            adjacent = [e.get(f"calibration_{m}_ms") for e in reps]
            if all(isinstance(c, (int, float)) and c > 0 for c in adjacent):
                ratios = [v / c for v, c in zip(values, adjacent)]
                out[m]["adjacent"] = statistics.median(ratios)
                out[m]["adjacent_noise"] = robust_noise(ratios)
        return out
    # --benchmark_report_aggregates_only: the median aggregate, noise from the cv one.
    agg = {e.get("aggregate_name"): e for e in entries}
    if "median" not in agg:
        return {"error": "no repetitions and no median aggregate"}
    out["repetitions"] = int(agg["median"].get("repetitions", 1))
    for m in METRICS:
        cv = agg.get("cv", {}).get(f"{m}_time")
        out[m] = {"median_ms": float(agg["median"][f"{m}_time"]) * TO_MS[agg["median"].get("time_unit", "ns")],
                  "noise": float(cv) if cv is not None else None}
    return out


def host_of(ctx: dict) -> dict:
    return {"cpu_model": ctx.get("cpu_model", "unknown"), "num_cpus": ctx.get("num_cpus"),
            "mhz_per_cpu": ctx.get("mhz_per_cpu"), "host_name": ctx.get("host_name")}


def same_host(a: dict, b: dict) -> bool:
    return a.get("cpu_model") == b.get("cpu_model") and a.get("num_cpus") == b.get("num_cpus")


def load_run(results: Path) -> dict:
    """The benchmarks of a results directory, keyed binary:name, in run order."""
    files = sorted(results.glob("*.json")) if results.is_dir() else []
    if not files:
        raise ValueError(f"no benchmark JSON files in {results}")
    run = {"host": None, "load_avg": {}, "benchmarks": {}}
    for path in files:
        data = json.loads(path.read_text(encoding="utf-8"))
        ctx, binary = data.get("context", {}), path.stem
        run["host"] = run["host"] or host_of(ctx)
        run["load_avg"][binary] = ctx.get("load_avg")
        grouped: dict[str, list[dict]] = {}
        # Registration order, whatever order random interleaving ran the repetitions in.
        for e in sorted(data.get("benchmarks", []),
                        key=lambda e: (e.get("family_index", 0), e.get("per_family_instance_index", 0))):
            grouped.setdefault(bench_key(binary, e.get("run_name", e.get("name", "?"))), []).append(e)
        calibration = bench_key(binary, CALIBRATION)
        for key, entries in grouped.items():
            b = {"binary": binary, **summarise(entries)}
            if key != calibration:
                b["calibration"] = calibration
            run["benchmarks"][key] = b
        # Normalised times: over the BM_Calibration of the same binary and run.
        cal = run["benchmarks"].get(calibration)
        for key, b in run["benchmarks"].items():
            if b.get("calibration") == calibration and cal and "error" not in cal and "error" not in b:
                for m in METRICS:
                    b[m]["normalised"] = b[m]["median_ms"] / cal[m]["median_ms"]
    return run


def git_commit() -> str:
    def git(*args):
        p = subprocess.run(["git", "-C", str(REPO_ROOT), *args], capture_output=True, text=True, timeout=60)
        return p.stdout.strip() if p.returncode == 0 else None
    try:
        commit = git("rev-parse", "--short", "HEAD") or "unknown"
        dirty = git("status", "--porcelain", "--untracked-files=no")
    except (OSError, subprocess.TimeoutExpired):
        return "unknown"
    return commit + ("-dirty" if dirty else "")


def save_baseline(run: dict, out: Path, note: str = "") -> None:
    baseline = {
        "schema": SCHEMA,
        "created": _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC"),
        "commit": git_commit(),
        "host": run["host"],
        "load_avg_at_start": run["load_avg"],
        "load_avg_at_save": [round(x, 2) for x in os.getloadavg()],
        "note": note,
        "benchmarks": run["benchmarks"],
    }
    out.write_text(json.dumps(baseline, indent=1) + "\n", encoding="utf-8")


def noise_of(entry: dict, metric: str, unknown_noise: float) -> float:
    v = entry.get(metric, {}).get("noise")
    return unknown_noise if v is None else v


def ratio_and_noise(b: dict, n: dict, base: dict, now: dict, metric: str, host_ok: bool,
                    unknown_noise: float) -> tuple[float | None, float | None, str]:
    """now / baseline of one benchmark, its relative noise, and what the ratio is of."""
    bm, nm = b.get(metric, {}), n.get(metric, {})
    if bm.get("adjacent") and nm.get("adjacent"):
        noises = [unknown_noise if x is None else x for x in (bm.get("adjacent_noise"), nm.get("adjacent_noise"))]
        return nm["adjacent"] / bm["adjacent"], max(noises), "normalised"
    if host_ok:
        noise = max(noise_of(b, metric, unknown_noise), noise_of(n, metric, unknown_noise))
        return nm["median_ms"] / bm["median_ms"], noise, "absolute"
    if bm.get("normalised") and nm.get("normalised"):  # by the binary's BM_Calibration, a poorer match
        cal_b, cal_n = base.get(b["calibration"], {}), now.get(n["calibration"], {})
        noise = math.hypot(max(noise_of(b, metric, unknown_noise), noise_of(n, metric, unknown_noise)),
                           max(noise_of(cal_b, metric, unknown_noise), noise_of(cal_n, metric, unknown_noise)))
        return nm["normalised"] / bm["normalised"], noise, "normalised by run"
    return None, None, ""


def compare(baseline: dict, run: dict, metric: str = "cpu", k: float = 3.0, floor: float = 0.05,
            unknown_noise: float = 0.05) -> tuple[list[dict], list[str]]:
    """One row per benchmark of either side, and the warnings."""
    warnings = []
    host_ok = same_host(baseline.get("host") or {}, run.get("host") or {})
    if not host_ok:
        warnings.append(f"host differs from the baseline's ({describe_host(baseline.get('host'))} then, "
                        f"{describe_host(run.get('host'))} now): only normalised times are compared")
    base, now = baseline.get("benchmarks", {}), run.get("benchmarks", {})
    other = METRICS[1 - METRICS.index(metric)]
    rows = []
    for key in list(base) + [k_ for k_ in now if k_ not in base]:
        b, n = base.get(key), now.get(key)
        row = {"benchmark": key, "baseline_ms": None, "now_ms": None, "ratio": None, "normalised_ratio": None,
               "other_ratio": None, "noise": None, "limit": None, "basis": ""}
        rows.append(row)
        if b is not None and "error" not in b:
            row["baseline_ms"] = b[metric]["median_ms"]
        if n is not None and "error" not in n:
            row["now_ms"] = n[metric]["median_ms"]
        if n is None:
            row["verdict"] = "not run"
        elif "error" in n:
            row["verdict"] = f"error: {n['error']}"
        elif b is None or "error" in b:
            row["verdict"] = "new"
        elif "calibration" not in n:
            row["ratio"] = row["now_ms"] / row["baseline_ms"]
            row["verdict"] = "reference"  # the machine's speed, now over then
        else:
            row["ratio"] = row["now_ms"] / row["baseline_ms"]
            ratio, noise, row["basis"] = ratio_and_noise(b, n, base, now, metric, host_ok, unknown_noise)
            if row["basis"].startswith("normalised"):
                row["normalised_ratio"] = ratio
            other_ratio, _, other_basis = ratio_and_noise(b, n, base, now, other, host_ok, unknown_noise)
            row["other_ratio"] = other_ratio if other_basis.startswith("normalised") else None
            if ratio is None:
                row["verdict"] = "not compared (no calibration)"
                continue
            row["noise"] = noise
            row["limit"] = 1.0 + max(k * noise, floor)
            row["verdict"] = ("slower" if ratio > row["limit"] else "faster" if ratio < 1.0 / row["limit"] else "ok")
    return rows, warnings


def describe_host(h: dict | None) -> str:
    h = h or {}
    return f"{h.get('cpu_model', '?')}, {h.get('num_cpus', '?')} CPUs"


def failed(rows: list[dict]) -> bool:
    return any(r["verdict"] == "slower" or r["verdict"].startswith("error") for r in rows)


def fmt(v, digits: int = 4) -> str:
    return "" if v is None else f"{v:.{digits}g}"


def not_run(rows: list[dict]) -> str:
    """One line for the baseline's benchmarks missing from this run (all but a --filter's)."""
    missing = [r["benchmark"] for r in rows if r["verdict"] == "not run"]
    if not missing:
        return ""
    return f"{len(missing)} of the baseline's benchmarks not run" + (": " + ", ".join(missing) if len(missing) <= 5
                                                                     else " (a --filter run?)")


def table(rows: list[dict], metric: str) -> tuple[list[str], list[list[str]]]:
    """The rows of the benchmarks that ran."""
    rows = [r for r in rows if r["verdict"] != "not run"]
    other = METRICS[1 - METRICS.index(metric)]
    header = ["benchmark", "baseline (ms)", "now (ms)", "ratio", "normalised ratio", "noise", "limit", "verdict",
              f"{other} normalised ratio"]
    body = [[r["benchmark"], fmt(r["baseline_ms"]), fmt(r["now_ms"]), fmt(r["ratio"], 3),
             fmt(r["normalised_ratio"], 3), "" if r["noise"] is None else f"{100 * r['noise']:.1f} %",
             fmt(r["limit"], 3), r["verdict"], fmt(r["other_ratio"], 3)] for r in rows]
    return header, body


def print_text(rows: list[dict], warnings: list[str], baseline: dict, metric: str) -> None:
    print(f"compare_baseline: {metric} time against baseline {baseline.get('commit', '?')} "
          f"({baseline.get('created', '?')}, {describe_host(baseline.get('host'))})")
    header, body = table(rows, metric)
    widths = [max(len(x) for x in col) for col in zip(header, *body)]
    for line in [header] + body:
        print("  ".join(x.ljust(w) if i == 0 else x.rjust(w) for i, (x, w) in enumerate(zip(line, widths))))
    if not_run(rows):
        print(f"compare_baseline: {not_run(rows)}")
    for w in warnings:
        print(f"compare_baseline: warning: {w}", file=sys.stderr)
    slower = [r["benchmark"] for r in rows if r["verdict"] == "slower"]
    print(f"compare_baseline: {len(slower)} slower" + (": " + ", ".join(slower) if slower else ""))


def markdown(rows: list[dict], warnings: list[str], baseline: dict, metric: str, k: float, floor: float) -> str:
    load = baseline.get("load_avg_at_start") or {}
    lines = ["## Comparison with the baseline", "",
             f"- baseline: `benchmarks/baseline.json`, commit `{baseline.get('commit', '?')}`, "
             f"{baseline.get('created', '?')}, {describe_host(baseline.get('host'))}; load average at the "
             "start of each binary: " + "; ".join(f"{b} {', '.join(fmt(x, 3) for x in v or [])}"
                                                 for b, v in load.items()),
             f"- {'CPU time of the process (all threads)' if metric == 'cpu' else 'wall (real) time'}, median "
             "over repetitions; ratio = now / baseline; normalised ratio = the same for the time divided, "
             "repetition by repetition, by the calibration work timed next to it (the verdict's basis; "
             "`benchmarks/compare_baseline.py`)",
             f"- slower when the normalised ratio exceeds the limit 1 + max({k:g} x noise, {100 * floor:g} %), "
             "faster below its inverse; noise = relative spread (1.4826 MAD / median) of the normalised time "
             "over repetitions, the larger of baseline and now; `BM_Calibration` rows (reference) show the "
             "machine's speed, now / then"]
    lines += [f"- ⚠ {w}" for w in warnings]
    header, body = table(rows, metric)
    lines += ["", "| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(x.replace("|", "\\|") for x in r) + " |" for r in body]
    lines += ["", not_run(rows) + "."] if not_run(rows) else []
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--results", type=Path, required=True, help="directory of Google Benchmark JSON files")
    ap.add_argument("--baseline", type=Path, help="baseline JSON to compare with")
    ap.add_argument("--save", type=Path, help="write the run as the baseline to this file instead")
    ap.add_argument("--note", default="", help="free text stored with a saved baseline")
    ap.add_argument("--markdown", type=Path, help="also write the comparison as a Markdown section")
    ap.add_argument("--metric", choices=METRICS, default="cpu", help="time compared (default: cpu)")
    ap.add_argument("--k", type=float, default=3.0, help="noise multiple of the limit (default 3)")
    ap.add_argument("--floor", type=float, default=0.05, help="smallest relative limit (default 0.05)")
    ap.add_argument("--unknown-noise", type=float, default=0.05,
                    help="relative noise assumed for a single repetition (default 0.05)")
    args = ap.parse_args(argv)
    try:
        run = load_run(args.results)
    except (OSError, ValueError, KeyError, TypeError) as e:
        print(f"compare_baseline: cannot read the run: {e}", file=sys.stderr)
        return 2
    if args.save:
        save_baseline(run, args.save, args.note)
        print(f"compare_baseline: saved {len(run['benchmarks'])} benchmarks to {args.save}")
        return 0
    if not args.baseline:
        ap.error("--baseline or --save is required")
    if not args.baseline.exists():
        print(f"compare_baseline: warning: no baseline at {args.baseline} (scripts/bench --save-baseline "
              "writes one); nothing compared", file=sys.stderr)
        if args.markdown:
            args.markdown.write_text("## Comparison with the baseline\n\nNo baseline stored.\n", encoding="utf-8")
        return 0
    try:
        baseline = json.loads(args.baseline.read_text(encoding="utf-8"))
    except (OSError, ValueError) as e:
        print(f"compare_baseline: cannot read {args.baseline}: {e}", file=sys.stderr)
        return 2
    rows, warnings = compare(baseline, run, args.metric, args.k, args.floor, args.unknown_noise)
    print_text(rows, warnings, baseline, args.metric)
    if args.markdown:
        args.markdown.write_text(markdown(rows, warnings, baseline, args.metric, args.k, args.floor),
                                 encoding="utf-8")
    return 1 if failed(rows) else 0


if __name__ == "__main__":
    sys.exit(main())
