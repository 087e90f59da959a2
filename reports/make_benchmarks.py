#!/usr/bin/python3
"""Write BENCHMARKS.md from Google Benchmark JSON files.

Usage:
    /usr/bin/python3 reports/make_benchmarks.py --results build/benchmark-results --out reports/BENCHMARKS.md \
        [--scaling reports/network_scaling.json]
    /usr/bin/python3 reports/make_benchmarks.py --scaling reports/network_scaling.json --out reports/BENCHMARKS.md

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

--scaling adds the section "Network scaling" from a run of bench_network_scaling: per
flow-Jacobian path (dense, krylov, augmented, and dense-cf, krylov-cf, augmented-cf with
a lumped face load and frictionless faces) and size, wetted nodes, blocks, CPU and wall time per coupled step,
one factorisation of K and their ratio, Newton and Krylov iterations, peak memory; the
exponent of time per step in wetted nodes fitted by least squares on log-log (sizes
>= 1,000 wetted nodes, and all sizes), the targets (at most N^1.2 from 1,000 to 10,000
wetted nodes; 10,000 wetted nodes in 4 GB) met, missed or not measured; the sizes that
did not run and why; and a log-log figure (figures/network_scaling.png next to the
report, drawn with matplotlib when it can be imported). Without --results only that
section of an existing report is rewritten (between its markers; appended if it has
none), so the scaling run, which takes about 15 minutes, is not repeated with the
others.

Exit status: 0 when the report was written from readable files; 1 when there were
no JSON files or one could not be read (the report is still written).

Standard library only (matplotlib for the scaling figure, if present).
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


# --- network scaling (bench_network_scaling) ------------------------------------------------

SCALING_BEGIN = "<!-- network-scaling:begin -->"
SCALING_END = "<!-- network-scaling:end -->"
# The flow-Jacobian argument was named `krylov` (0 dense, 1 krylov) before the augmented
# path (2) was added and it was renamed `jacobian`; stored runs use either name.
SCALING_NAME = re.compile(r"BM_NetworkScaling/ribs:(\d+)/(?:krylov|jacobian):([012])(?:/conjugate_frictionless:([01]))?")
# The paths in report order, indexed by jacobian + 3 conjugate_frictionless (absent: 0, runs before it had it).
SCALING_PATHS = ("dense", "krylov", "augmented", "dense-cf", "krylov-cf", "augmented-cf")
SCALING_FIGURE = "figures/network_scaling.png"
TARGET_EXPONENT = 1.2            # time per step at most N^1.2 ...
TARGET_NODES = (1000, 10000)     # ... from 1,000 to 10,000 wetted nodes
MEMORY_TARGET_MB = 4096.0        # 10,000 wetted nodes in 4 GB
# bench_network_scaling's message for a size stopped at the time cap: the phase, and the
# peak resident memory of the size's process until the stop.
CAPPED_MEMORY = re.compile(r"over the time cap: (.+?) used .*\(peak resident memory until then (\d+(?:\.\d+)?) MB\)")
MEMORY_TARGET_NODES = 10000


def fishbone_nodes(ribs: int) -> int:
    """Wetted nodes of the benchmark's network (bench_network_scaling.cpp): 24 ribs^2 + 1."""
    return 24 * ribs * ribs + 1


def scaling_rows(benches: list[dict]) -> list[dict]:
    """One row per path and size: measured counters, or the error that stopped it; in path order."""
    rows = []
    for b in select_rows(benches):
        m = SCALING_NAME.search(str(b.get("name", "")))
        if not m:
            continue
        ribs = int(m.group(1))
        row = {k: float(v) for k, v in b.items() if is_number(v) and k not in STANDARD_KEYS}
        path = SCALING_PATHS[int(m.group(2)) + 3 * int(m.group(3) or 0)]
        row.update({"path": path, "ribs": ribs, "error": failed(b),
                    "nodes": int(b["wetted_nodes"]) if is_number(b.get("wetted_nodes")) else fishbone_nodes(ribs)})
        rows.append(row)
    return sorted(rows, key=lambda r: (SCALING_PATHS.index(r["path"]), r["nodes"]))


def present_paths(rows: list[dict]) -> list[str]:
    """The paths with at least one row (measured or not), in report order."""
    return [p for p in SCALING_PATHS if any(r["path"] == p for r in rows)]


def fit_power_law(points: list[tuple[float, float]]) -> tuple[float, float] | None:
    """Least squares of ln y on ln x: (exponent, prefactor) of y = c x^a; None with fewer
    than two distinct x."""
    pts = [(math.log(x), math.log(y)) for x, y in points if x > 0 and y > 0]
    if len({x for x, _ in pts}) < 2:
        return None
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    slope = sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)
    return slope, math.exp(my - slope * mx)


def measured(rows: list[dict], path: str) -> list[dict]:
    return [r for r in rows if r["path"] == path and r["error"] is None and is_number(r.get("step_cpu_s"))]


def scaling_fits(rows: list[dict]) -> dict:
    """Per path: the exponent of CPU time per step over sizes >= 1,000 wetted nodes and over
    all sizes, with the node range and count of sizes of each fit."""
    fits = {}
    for path in present_paths(rows):
        ok = measured(rows, path)
        for label, subset in (("from_1000", [r for r in ok if r["nodes"] >= TARGET_NODES[0]]), ("all", ok)):
            fit = fit_power_law([(r["nodes"], r["step_cpu_s"]) for r in subset])
            fits[(path, label)] = None if fit is None else {
                "exponent": fit[0], "prefactor": fit[1], "sizes": len(subset),
                "nodes": (min(r["nodes"] for r in subset), max(r["nodes"] for r in subset))}
        fit = fit_power_law([(r["nodes"], r["factorize_cpu_s"]) for r in ok if is_number(r.get("factorize_cpu_s"))])
        fits[(path, "factorisation")] = None if fit is None else {"exponent": fit[0], "prefactor": fit[1]}
    return fits


def n_fmt(n: float) -> str:
    return f"{int(round(n)):,}"


def time_verdict(rows: list[dict], fits: dict) -> list[str]:
    lines = []
    for path in present_paths(rows):
        fit = fits.get((path, "from_1000"))
        ok = measured(rows, path)
        largest = max((r["nodes"] for r in ok), default=0)
        if fit is None:
            n_big = sum(1 for r in ok if r["nodes"] >= TARGET_NODES[0])
            why = ("no size with 1,000 or more wetted nodes ran" if n_big == 0
                   else "only one size with 1,000 or more wetted nodes ran")
            lines.append(f"- **{path}: not met (not measured)**: {why} within the cap "
                         f"(largest measured: {n_fmt(largest) if largest else 'none'} wetted nodes), "
                         "so the exponent from 1,000 to 10,000 could not be fitted.")
            continue
        a, (lo, hi) = fit["exponent"], fit["nodes"]
        if a > TARGET_EXPONENT:
            verdict = "missed"
        elif hi >= TARGET_NODES[1]:
            verdict = "met"
        else:
            verdict = f"met up to {n_fmt(hi)} wetted nodes, not measured beyond"
        lines.append(f"- **{path}: {verdict}**: exponent {a:.2f} against {TARGET_EXPONENT} "
                     f"({fit['sizes']} sizes, {n_fmt(lo)} to {n_fmt(hi)} wetted nodes).")
    return lines


def memory_verdict(rows: list[dict]) -> list[str]:
    lines = []
    for path in present_paths(rows):
        ok = measured(rows, path)
        big = [r for r in ok if r["nodes"] >= MEMORY_TARGET_NODES and is_number(r.get("peak_rss_mb"))]
        if big:
            r = min(big, key=lambda r: r["nodes"])
            met = r["peak_rss_mb"] <= MEMORY_TARGET_MB
            lines.append(f"- **{path}: {'met' if met else 'missed'}**: {n_fmt(r['nodes'])} wetted nodes peaked at "
                         f"{r['peak_rss_mb']:,.0f} MB.")
            continue
        with_memory = [r for r in ok if is_number(r.get("peak_rss_mb"))]
        largest = max(with_memory, key=lambda r: r["nodes"], default=None)
        at = (f"largest measured: {n_fmt(largest['nodes'])} wetted nodes at {largest['peak_rss_mb']:,.0f} MB"
              if largest else "nothing measured")
        # A size of the target stopped at the time cap still says how much memory it had
        # used by then: a lower bound of its peak, reported as such, never as met.
        capped = [(r, CAPPED_MEMORY.search(r["error"] or "")) for r in rows
                  if r["path"] == path and r["nodes"] >= MEMORY_TARGET_NODES]
        capped = [(r, float(m.group(2))) for r, m in capped if m]
        if capped:
            r, used = min(capped, key=lambda c: c[0]["nodes"])
            phase = CAPPED_MEMORY.search(r["error"]).group(1)
            lines.append(f"- **{path}: not measured to the end of a step**: {n_fmt(r['nodes'])} wetted nodes had "
                         f"used {used:,.0f} MB when the time cap stopped them ({phase}), a lower bound of the "
                         f"peak ({at}).")
            continue
        lines.append(f"- **{path}: not measured**: no size with {MEMORY_TARGET_NODES:,} or more wetted nodes "
                     f"ran within the cap ({at}).")
    return lines


def scaling_observations(rows: list[dict]) -> list[str]:
    """Per path, from the smallest to the largest measured size: Newton iterations per step,
    and the share of building S (dense paths) or Krylov iterations per Newton iteration (krylov
    paths) at the largest."""
    lines = []
    for path in present_paths(rows):
        ok = measured(rows, path)
        if len(ok) < 2:
            continue
        first, last = ok[0], ok[-1]
        text = (f"- {path}: Newton iterations per step {fmt(first.get('newton_per_step'))} at "
                f"{n_fmt(first['nodes'])} wetted nodes, {fmt(last.get('newton_per_step'))} at {n_fmt(last['nodes'])}")
        if path.startswith("dense") and is_number(last.get("sensitivity_s_per_step")) and last.get("step_s"):
            text += (f"; building S took {100 * last['sensitivity_s_per_step'] / last['step_s']:.0f} % of the wall "
                     f"time per step at {n_fmt(last['nodes'])}")
        if path.startswith("krylov") and last.get("newton_per_step"):
            text += (f"; {last.get('krylov_per_step', 0) / last['newton_per_step']:.0f} Krylov iterations per Newton "
                     f"iteration at {n_fmt(last['nodes'])}")
        lines.append(text + ".")
    return lines + [""] if lines else []


def draw_scaling_figure(rows: list[dict], fits: dict, cap_s: float | None, path: Path) -> str | None:
    """The log-log figure; None when drawn, else why not."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as e:  # the report stays standard-library only
        return f"matplotlib unavailable ({e})"
    fig, ax = plt.subplots(figsize=(10.0, 5.0))
    # Per path: colour, marker, and where its sizes not measured are drawn relative to the cap line
    # (above and below it in turn, so that all paths show).
    styles = zip(SCALING_PATHS, ("tab:blue", "tab:orange", "tab:purple", "tab:green", "tab:red", "tab:brown"),
                 ("o", "s", "v", "^", "D", "P"), (1.25, 0.8, 1.1, 1.5, 0.65, 0.9))
    all_nodes, present = [r["nodes"] for r in rows], present_paths(rows)
    for p, colour, marker, cap_factor in (s for s in styles if s[0] in present):
        ok = measured(rows, p)
        if ok:
            ax.loglog([r["nodes"] for r in ok], [r["step_cpu_s"] for r in ok], marker=marker, color=colour,
                      label=f"{p}: CPU time per coupled step")
            fk = [r for r in ok if is_number(r.get("factorize_cpu_s"))]
            ax.loglog([r["nodes"] for r in fk], [r["factorize_cpu_s"] for r in fk], marker=marker, color=colour,
                      linestyle=":", markerfacecolor="none", label=f"{p}: one factorisation of K")
        for label, style in (("all", "--"), ("from_1000", "-.")):
            fit = fits.get((p, label))
            if fit:
                lo, hi = fit["nodes"]
                xs = [lo, hi]
                ax.loglog(xs, [fit["prefactor"] * x ** fit["exponent"] for x in xs], linestyle=style, color=colour,
                          alpha=0.6, label=f"{p}: fit {'all sizes' if label == 'all' else '>= 1,000'}: "
                                           f"N^{fit['exponent']:.2f}")
        if cap_s:
            stopped = [r["nodes"] for r in rows if r["path"] == p and r["error"] is not None]
            if stopped:
                ax.loglog(stopped, [cap_s * cap_factor] * len(stopped), linestyle="none", marker="x", color=colour,
                          label=f"{p}: not measured (over the cap or not started), drawn at the cap")
    measured_rows = [r for r in rows if r["error"] is None and is_number(r.get("step_cpu_s"))]
    if measured_rows:
        # A slope guide from a measured point, not a value: where N^1.2 would lead from there.
        anchor = min(measured_rows, key=lambda r: abs(math.log(r["nodes"] / TARGET_NODES[0])))
        xs = [anchor["nodes"], TARGET_NODES[1]]
        c = anchor["step_cpu_s"] / anchor["nodes"] ** TARGET_EXPONENT
        ax.loglog(xs, [c * x ** TARGET_EXPONENT for x in xs], color="grey", linestyle="--",
                  label=f"slope of the target, N^{TARGET_EXPONENT}, from the measured size nearest 1,000")
    if cap_s:
        ax.axhline(cap_s, color="red", linewidth=0.8, alpha=0.6, label=f"cap: {cap_s:g} s CPU per step")
    if all_nodes:
        ax.set_xlim(min(all_nodes) / 1.5, max(max(all_nodes), TARGET_NODES[1]) * 1.5)
    ax.set_xlabel("wetted nodes N")
    ax.set_ylabel("seconds (CPU)")
    ax.set_title("Coupled step and factorisation of K against network size")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return None


def scaling_section(results: Path, figure_path: Path | None) -> tuple[list[str], bool]:
    """The section "Network scaling" between its markers; False if the file is unreadable."""
    lines = [SCALING_BEGIN, "## Network scaling", ""]
    try:
        ctx, benches = read_results(results)
    except (OSError, ValueError, AttributeError) as e:
        return lines + [f"**Unreadable:** `{results.name}`: {e}", "", SCALING_END], False
    rows = scaling_rows(benches)
    cap = ctx.get("step_cap_s")
    try:
        cap_s = float(cap) if cap is not None else None
    except (TypeError, ValueError):
        cap_s = None
    load = ", ".join(fmt(x) for x in ctx["load_avg"]) if isinstance(ctx.get("load_avg"), list) else "?"
    cf = any(p.endswith("-cf") for p in present_paths(rows))
    lines += [
        f"From `{results.name}` (`benchmarks/bench_network_scaling.cpp`, run by `scripts/bench --scaling`): "
        f"run {ctx.get('date', '?')}, host {ctx.get('host_name', '?')} ({ctx.get('num_cpus', '?')} CPUs, "
        f"{ctx.get('cpu_model', '?')}), load average at the start {load}, HFDDA {ctx.get('hfdda_build_type', '?')}, "
        f"{ctx.get('hfdda_threads', '?')}.",
        "",
        "The case: a fishbone network of fractures already open and full of fluid (a trunk through the centre, "
        "ribs 8 m apart crossing it, a 4 m branch crossing each rib every 2 m; 24 ribs^2 + 1 wetted nodes) on a "
        "structured mesh of 1 m triangles whose domain grows with the network; fluid at 0.1 MPa in the volume "
        "that pressure opens (`initial_opening: elastic`: the rock in equilibrium with it at t = 0, design "
        "notes section 31), 0.5 kg/s injected at the centre, steps of 1 s, unbreakable joints (the network does not "
        "change), penalty contacts. Why this network and these settings: the comment at the top of "
        "`bench_network_scaling.cpp`. Per size, in a process of its own: one untimed warm-up step, then "
        f"{ctx.get('timed_steps', '?')} timed steps, then one factorisation of K (`assemble_and_factorise`, "
        f"median of 3). A size is stopped when one phase (model build, a step) uses more than "
        f"{cap if cap is not None else '?'} s of CPU time, and the larger sizes of its path are then not started."
        " The paths: dense (S formed, the flow Jacobian factorised densely), krylov (S applied as an operator, one "
        "solve with K per product; GMRES with a two-level preconditioner) and augmented (S applied as an operator; "
        "each flow Newton step one sparse LU of the mass balance together with the block displacements, design "
        "notes section 46)."
        + (" Paths marked -cf run the same networks with the fluid's face load lumped at the joint ends "
           "(`numerics.fluid_load: lumped`, the load work-conjugate to the lumped nodal volumes, design notes "
           "section 19) and frictionless fracture faces (`friction_angle: 0`, design notes section 31); the others "
           "with the seed's integrated face load and 30-degree friction." if cf else ""),
        "",
        "Times are CPU seconds of the process (one thread), the measure used for the fits and the ratio: the "
        "machine is shared, and a busy neighbour stretches wall time (given beside it) more than CPU time. "
        "Iterations are per timed step; Krylov iterations count on the krylov "
        f"{'paths' if cf else 'path'} only, products with S on the krylov and augmented ones; they "
        "cover the last attempt of a step that was cut. Memory is the peak resident set of the size's "
        "process.",
        ""]
    ok_rows = [r for r in rows if r["error"] is None]
    if ok_rows:
        lines += ["| path | ribs | wetted nodes | blocks | CPU s / step | wall s / step | factorisation of K (CPU s) "
                  "| step / factorisation | Newton its / step | Krylov its / step | S products / step "
                  "| open-close its / step | building S, or its operator (wall s / step) | warm-up step (CPU s, Newton its) "
                  "| peak memory (MB) |",
                  "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in ok_rows:
            g = lambda k: fmt(r.get(k))  # noqa: E731
            lines.append(f"| {r['path']} | {r['ribs']} | {n_fmt(r['nodes'])} | {n_fmt(r.get('blocks', 0))} "
                         f"| {g('step_cpu_s')} | {g('step_s')} | {g('factorize_cpu_s')} | {g('step_over_factorize')} "
                         f"| {g('newton_per_step')} | {g('krylov_per_step')} | {g('s_products_per_step')} "
                         f"| {g('outer_per_step')} | {g('sensitivity_s_per_step')} "
                         f"| {g('warm_up_cpu_s')}, {g('warm_up_newton_per_step')} | {fmt(round(r.get('peak_rss_mb', 0)))} |")
        lines.append("")
    else:
        lines += ["No size was measured.", ""]
    lines += scaling_observations(rows)
    stopped = [r for r in rows if r["error"] is not None]
    if stopped:
        lines += ["Not measured:", ""]
        lines += [f"- {r['path']}, {r['ribs']} ribs ({n_fmt(r['nodes'])} wetted nodes): {fmt(r['error'])}"
                  for r in stopped]
        lines.append("")

    fits = scaling_fits(rows)
    lines += ["Fitted exponent a of CPU time per step ~ N^a (least squares on log-log):", "",
              "| path | sizes >= 1,000 wetted nodes | all sizes | one factorisation of K, all sizes |",
              "|---|---|---|---|"]
    for p in present_paths(rows):
        cells = []
        for label in ("from_1000", "all"):
            f = fits.get((p, label))
            cells.append("not measured (fewer than 2 sizes)" if f is None else
                         f"{f['exponent']:.2f} ({f['sizes']} sizes, {n_fmt(f['nodes'][0])}-{n_fmt(f['nodes'][1])})")
        f = fits.get((p, "factorisation"))
        cells.append("" if f is None else f"{f['exponent']:.2f}")
        lines.append(f"| {p} | " + " | ".join(cells) + " |")
    lines += ["",
              f"Target: time per coupled step growing at most as N^{TARGET_EXPONENT} from "
              f"{TARGET_NODES[0]:,} to {TARGET_NODES[1]:,} wetted nodes:", ""]
    lines += time_verdict(rows, fits)
    lines += ["", f"Target: {MEMORY_TARGET_NODES:,} wetted nodes in {MEMORY_TARGET_MB / 1024:g} GB:", ""]
    lines += memory_verdict(rows)
    lines.append("")
    if figure_path is not None:
        why_not = draw_scaling_figure(rows, fits, cap_s, figure_path)
        lines += ([f"![Network scaling]({SCALING_FIGURE})", ""] if why_not is None
                  else [f"Figure not drawn: {why_not}.", ""])
    lines.append(SCALING_END)
    return lines, True


def replace_scaling_section(text: str, section: list[str]) -> str:
    """The report with its scaling section replaced, or appended if it has none."""
    block = "\n".join(section)
    begin, end = text.find(SCALING_BEGIN), text.find(SCALING_END)
    if begin >= 0 and end > begin:
        return text[:begin] + block + text[end + len(SCALING_END):]
    return text.rstrip("\n") + "\n\n" + block + "\n"


def update_scaling_section(scaling: Path, out: Path) -> int:
    section, ok = scaling_section(scaling, out.parent / SCALING_FIGURE)
    try:
        text = out.read_text(encoding="utf-8")
    except OSError:
        text = "# HFDDA benchmarks\n"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(replace_scaling_section(text, section).rstrip("\n") + "\n", encoding="utf-8")
    print(f"make_benchmarks: scaling section from {scaling}; wrote {out}", file=sys.stdout if ok else sys.stderr)
    return 0 if ok else 1


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


def write_report(results: Path, out: Path, comparison: Path | None = None, scaling: Path | None = None) -> int:
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
    if scaling is not None:
        section, readable = scaling_section(scaling, out.parent / SCALING_FIGURE)
        ok &= readable
        lines += section + [""]
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
    ap.add_argument("--results", type=Path, help="directory of Google Benchmark JSON files")
    ap.add_argument("--out", type=Path, required=True, help="markdown file to write")
    ap.add_argument("--comparison", type=Path, help="Markdown section to include (baseline comparison)")
    ap.add_argument("--scaling", type=Path, help="JSON of bench_network_scaling: the section 'Network scaling' "
                                                 "(alone, without --results: only that section of --out rewritten)")
    args = ap.parse_args(argv)
    if args.results is None:
        if args.scaling is None:
            ap.error("give --results, --scaling or both")
        return update_scaling_section(args.scaling, args.out)
    return write_report(args.results, args.out, args.comparison, args.scaling)


if __name__ == "__main__":
    sys.exit(main())
