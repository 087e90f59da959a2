#!/usr/bin/python3
"""Tests of the benchmark report (make_benchmarks.py): the timing tables and the network
scaling section. Run: cd reports && /usr/bin/python3 -m unittest test_make_benchmarks."""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.dont_write_bytecode = True  # keep reports/ free of __pycache__
sys.path.insert(0, str(HERE))

import make_benchmarks  # noqa: E402


BENCH_JSON = {
    "context": {"date": "2024-01-01T00:00:00+00:00", "host_name": "ci", "executable": "build/bin/bench_step",
                "num_cpus": 2, "mhz_per_cpu": 2400, "cpu_scaling_enabled": False,
                "caches": [], "load_avg": [0.5, 0.4, 0.3], "library_build_type": "release",
                "hfdda_build_type": "Release"},
    "benchmarks": [
        {"name": "BM_CoupledStep/2250", "run_name": "BM_CoupledStep/2250", "run_type": "iteration",
         "repetitions": 1, "repetition_index": 0, "threads": 1, "iterations": 3,
         "real_time": 2.5e9, "cpu_time": 2.4e9, "time_unit": "ns", "blocks": 2250.0, "target_s": 2.0},
        {"name": "BM_CoupledStep/512", "run_name": "BM_CoupledStep/512", "run_type": "iteration",
         "repetitions": 1, "repetition_index": 0, "threads": 1, "iterations": 10,
         "real_time": 150.0, "cpu_time": 140.0, "time_unit": "ms", "blocks": 512.0, "target_s": 1.0},
        {"name": "BM_Factorise/512", "run_type": "iteration", "iterations": 100,
         "real_time": 1500.0, "cpu_time": 1490.0, "time_unit": "us", "nnz": 4.2e4},
        {"name": "BM_Broken", "run_type": "iteration", "iterations": 0, "real_time": 0, "cpu_time": 0,
         "time_unit": "ns", "error_occurred": True, "error_message": "solver diverged"},
    ],
}


class MakeBenchmarksTest(unittest.TestCase):
    def test_benchmark_table(self):
        with tempfile.TemporaryDirectory() as tmp:
            results = Path(tmp) / "bench"
            results.mkdir()
            (results / "bench_step.json").write_text(json.dumps(BENCH_JSON), encoding="utf-8")
            out = Path(tmp) / "BENCHMARKS.md"
            p = subprocess.run([sys.executable, str(HERE / "make_benchmarks.py"), "--results", str(results),
                                "--out", str(out)], capture_output=True, text=True, timeout=120)
            self.assertEqual(p.returncode, 0, p.stderr)
            md = out.read_text(encoding="utf-8")
        self.assertIn("## bench_step", md)
        self.assertIn("2 CPUs at 2400 MHz", md)
        self.assertIn("benchmark library build type: release", md)
        self.assertIn("hfdda_build_type: Release", md)
        self.assertIn("| benchmark | real time (ms) | cpu time (ms) | iterations | blocks | target_s | nnz "
                      "| meets target |", md)
        self.assertIn("| BM_CoupledStep/2250 | 2500 | 2400 | 3 | 2250 | 2 |  | no ❌ (1.25x) |", md)
        self.assertIn("| BM_CoupledStep/512 | 150 | 140 | 10 | 512 | 1 |  | yes ✅ |", md)
        self.assertIn("| BM_Factorise/512 | 1.5 | 1.49 | 100 |  |  | 42000 |  |", md)
        self.assertIn("| BM_Broken | error: solver diverged |", md)

    def test_repetitions_and_threads_table(self):
        results = HERE.parent / "benchmarks" / "testdata" / "run"
        with tempfile.TemporaryDirectory() as tmp:
            out, comparison = Path(tmp) / "BENCHMARKS.md", Path(tmp) / "cmp.md"
            comparison.write_text("## Comparison with the baseline\n\nstub\n", encoding="utf-8")
            self.assertEqual(make_benchmarks.write_report(results, out, comparison), 0)
            md = out.read_text(encoding="utf-8")
        self.assertIn("## Comparison with the baseline\n\nstub\n", md)
        self.assertIn("median of up to 5 repetitions", md)
        # One row per benchmark: the median aggregate, not the repetitions.
        self.assertEqual(md.count("| BM_Step/cells:16/threads:1/process_time/real_time"), 1)
        self.assertIn("| BM_Step/cells:16/threads:1/process_time/real_time_median | 10 | 9.8 | 5 |", md)
        self.assertIn("| BM_Step/cells:16 | 1024 | 1 | 10 | 9.8 |  |  |  |", md)
        self.assertIn("| BM_Step/cells:16 | 1024 | 2 | 8 | 15.2 | 1.25 | 1.55 |  |", md)
        self.assertLess(md.index("## Comparison"), md.index("## Threads: 1 vs 2"))

    def test_no_benchmarks(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = Path(tmp) / "BENCHMARKS.md"
            self.assertEqual(make_benchmarks.write_report(Path(tmp) / "none", out), 1)
            self.assertIn("No benchmark results found", out.read_text(encoding="utf-8"))


def scaling_benchmark(ribs: int, krylov: int, step_cpu_s: float = 0.0, peak_rss_mb: float = 0.0,
                      error: str | None = None, cf: int | None = None) -> dict:
    """A row of bench_network_scaling's JSON (fishbone network: 24 ribs^2 + 1 wetted nodes);
    cf None: a name without the conjugate_frictionless argument (runs from before it).
    krylov 2: the augmented path, under the argument's later name `jacobian`."""
    arg = "" if cf is None else f"/conjugate_frictionless:{cf}"
    argument = "jacobian" if krylov == 2 else "krylov"
    name = f"BM_NetworkScaling/ribs:{ribs}/{argument}:{krylov}{arg}/iterations:1/manual_time"
    b = {"name": name, "run_name": name, "run_type": "iteration", "family_index": 1,
         "per_family_instance_index": ribs + 100 * krylov + 200 * (cf or 0), "repetitions": 1,
         "repetition_index": 0, "threads": 1, "iterations": 1, "real_time": 1.3 * step_cpu_s, "cpu_time": 0.01,
         "time_unit": "s", "label": ("krylov" if krylov else "dense") + ("-cf" if cf else "")}
    if error is not None:
        b.update({"error_occurred": True, "error_message": error, "real_time": 0.0})
        return b
    nodes = 24 * ribs * ribs + 1
    b.update({"wetted_nodes": nodes, "blocks": 6.0 * nodes, "step_cpu_s": step_cpu_s, "step_s": 1.3 * step_cpu_s,
              "factorize_cpu_s": 1e-5 * nodes, "step_over_factorize": step_cpu_s / (1e-5 * nodes),
              "newton_per_step": 250.0, "krylov_per_step": 2400.0 if krylov else 0.0,
              "s_products_per_step": 2600.0 if krylov else 0.0, "outer_per_step": 9.0,
              "sensitivity_s_per_step": 0.5 * step_cpu_s, "warm_up_cpu_s": 2.0 * step_cpu_s,
              "warm_up_newton_per_step": 369.0, "peak_rss_mb": peak_rss_mb})
    return b


SCALING_CONTEXT = {"date": "2026-11-25T17:00:00+00:00", "host_name": "vm", "num_cpus": 2,
                   "load_avg": [2.0, 2.1, 2.2], "cpu_model": "AMD EPYC", "hfdda_build_type": "Release",
                   "hfdda_threads": "threads: 1", "step_cap_s": "120", "timed_steps": "2"}


def write_scaling(path: Path, benchmarks: list[dict]) -> Path:
    path.write_text(json.dumps({"context": SCALING_CONTEXT, "benchmarks": benchmarks}), encoding="utf-8")
    return path


class NetworkScalingTest(unittest.TestCase):
    # Dense: 97, 1,177 and 1,945 wetted nodes on t = 1e-3 N^1.5, 2,905 over the cap;
    # krylov: 97 measured, 217 over the cap.
    RUN = [scaling_benchmark(2, 0, 1e-3 * 97 ** 1.5, 70.0), scaling_benchmark(7, 0, 1e-3 * 1177 ** 1.5, 210.0),
           scaling_benchmark(9, 0, 1e-3 * 1945 ** 1.5, 420.0),
           scaling_benchmark(11, 0, error="over the time cap: timed step 1 used 121 s CPU (130 s wall), cap 120 s "
                                          "CPU per phase; stopped (peak resident memory until then 900 MB)"),
           scaling_benchmark(2, 1, 0.5, 72.0),
           scaling_benchmark(3, 1, error="over the time cap: warm-up step 1 used 121 s CPU"),
           scaling_benchmark(4, 1, error="not run: over the time cap at a smaller size (3 ribs, 217 wetted nodes)")]

    def test_fit_power_law(self):
        a, c = make_benchmarks.fit_power_law([(100.0, 3.0 * 100 ** 1.2), (1000.0, 3.0 * 1000 ** 1.2),
                                              (5000.0, 3.0 * 5000 ** 1.2)])
        self.assertAlmostEqual(a, 1.2, places=12)
        self.assertAlmostEqual(c, 3.0, places=9)
        self.assertIsNone(make_benchmarks.fit_power_law([(100.0, 1.0)]))
        self.assertIsNone(make_benchmarks.fit_power_law([(100.0, 1.0), (100.0, 2.0)]))

    def test_section_table_fits_and_verdicts(self):
        with tempfile.TemporaryDirectory() as tmp:
            scaling = write_scaling(Path(tmp) / "network_scaling.json", self.RUN)
            lines, ok = make_benchmarks.scaling_section(scaling, None)
        self.assertTrue(ok)
        md = "\n".join(lines)
        self.assertTrue(md.startswith(make_benchmarks.SCALING_BEGIN))
        self.assertTrue(md.endswith(make_benchmarks.SCALING_END))
        self.assertIn("| dense | 7 | 1,177 | 7,062 | 40.38 | 52.49 | 0.01177 | 3431 | 250 | 0 | 0 | 9 | 20.19 "
                      "| 80.76, 369 | 210 |", md)
        self.assertIn("| krylov | 2 | 97 | 582 | 0.5 | 0.65 |", md)
        self.assertIn("- dense, 11 ribs (2,905 wetted nodes): over the time cap: timed step 1 used 121 s CPU", md)
        self.assertIn("- krylov, 4 ribs (385 wetted nodes): not run: over the time cap at a smaller size", md)
        self.assertIn("| dense | 1.50 (2 sizes, 1,177-1,945) | 1.50 (3 sizes, 97-1,945) | 1.00 |", md)
        self.assertIn("| krylov | not measured (fewer than 2 sizes) | not measured (fewer than 2 sizes) |", md)
        self.assertIn("- **dense: missed**: exponent 1.50 against 1.2 (2 sizes, 1,177 to 1,945 wetted nodes).", md)
        self.assertIn("- **krylov: not met (not measured)**: no size with 1,000 or more wetted nodes ran", md)
        self.assertIn("- **dense: not measured**: no size with 10,000 or more wetted nodes ran within the cap "
                      "(largest measured: 1,945 wetted nodes at 420 MB).", md)
        self.assertIn("- dense: Newton iterations per step 250 at 97 wetted nodes, 250 at 1,945; building S took "
                      "38 % of the wall time per step at 1,945.", md)
        self.assertIn("120 s of CPU time", md)

    def test_targets_met(self):
        # N^1.1 from 1,177 to 10,585 wetted nodes and 3 GB at 10,585: both targets met.
        run = [scaling_benchmark(r, 0, 1e-2 * (24 * r * r + 1) ** 1.1, 3000.0 * r / 21) for r in (7, 14, 21)]
        with tempfile.TemporaryDirectory() as tmp:
            md = "\n".join(make_benchmarks.scaling_section(write_scaling(Path(tmp) / "s.json", run), None)[0])
        self.assertIn("- **dense: met**: exponent 1.10 against 1.2 (3 sizes, 1,177 to 10,585 wetted nodes).", md)
        self.assertIn("- **dense: met**: 10,585 wetted nodes peaked at 3,000 MB.", md)
        # The same slope up to 4,705 wetted nodes only: met there, the rest not measured.
        with tempfile.TemporaryDirectory() as tmp:
            md = "\n".join(make_benchmarks.scaling_section(write_scaling(Path(tmp) / "s.json", run[:2]), None)[0])
        self.assertIn("- **dense: met up to 4,705 wetted nodes, not measured beyond**", md)

    def test_memory_target_missed(self):
        run = [scaling_benchmark(2, 0, 1.0, 80.0), scaling_benchmark(21, 0, 900.0, 5200.0)]
        with tempfile.TemporaryDirectory() as tmp:
            md = "\n".join(make_benchmarks.scaling_section(write_scaling(Path(tmp) / "s.json", run), None)[0])
        self.assertIn("- **dense: missed**: 10,585 wetted nodes peaked at 5,200 MB.", md)

    def test_memory_of_a_target_size_stopped_at_the_cap_is_a_lower_bound(self):
        # 10,585 wetted nodes stopped in its warm-up step at 2,540 MB: reported as used until the stop,
        # never as met; a smaller size stopped at the cap does not count.
        stop = ("over the time cap: warm-up step 1 used 1200 s CPU (1210 s wall), cap 1200 s CPU per phase; "
                "stopped (peak resident memory until then {} MB)")
        run = [scaling_benchmark(2, 1, 1.0, 80.0, cf=1), scaling_benchmark(14, 1, error=stop.format(1600), cf=1),
               scaling_benchmark(21, 1, error=stop.format(2540), cf=1)]
        with tempfile.TemporaryDirectory() as tmp:
            md = "\n".join(make_benchmarks.scaling_section(write_scaling(Path(tmp) / "s.json", run), None)[0])
        self.assertIn("- **krylov-cf: not measured to the end of a step**: 10,585 wetted nodes had used 2,540 MB "
                      "when the time cap stopped them (warm-up step 1), a lower bound of the peak (largest "
                      "measured: 97 wetted nodes at 80 MB).", md)
        self.assertNotIn("krylov-cf: met", md)
        # Without the target size, the stopped 4,705-node size leaves the target not measured.
        with tempfile.TemporaryDirectory() as tmp:
            md = "\n".join(make_benchmarks.scaling_section(write_scaling(Path(tmp) / "s.json", run[:2]), None)[0])
        self.assertIn("- **krylov-cf: not measured**: no size with 10,000 or more wetted nodes ran within the cap", md)

    def test_four_paths(self):
        # dense (names without the argument and with conjugate_frictionless:0): N^1.5; krylov: N^1.1 up to
        # 4,705 wetted nodes; dense-cf: N^1.3 up to 10,585 in 3 GB; krylov-cf: 97 measured, 217 over the cap.
        n = lambda ribs: 24 * ribs * ribs + 1  # noqa: E731
        run = [scaling_benchmark(7, 0, 1e-3 * n(7) ** 1.5, 210.0),
               scaling_benchmark(9, 0, 1e-3 * n(9) ** 1.5, 420.0, cf=0),
               scaling_benchmark(7, 1, 1e-2 * n(7) ** 1.1, 200.0, cf=0),
               scaling_benchmark(14, 1, 1e-2 * n(14) ** 1.1, 900.0, cf=0),
               scaling_benchmark(7, 0, 1e-3 * n(7) ** 1.3, 300.0, cf=1),
               scaling_benchmark(21, 0, 1e-3 * n(21) ** 1.3, 3000.0, cf=1),
               scaling_benchmark(2, 1, 0.5, 72.0, cf=1),
               scaling_benchmark(3, 1, error="over the time cap: warm-up step 1 used 121 s CPU", cf=1)]
        rows = make_benchmarks.scaling_rows(run)
        self.assertEqual([(r["path"], r["ribs"]) for r in rows],
                         [("dense", 7), ("dense", 9), ("krylov", 7), ("krylov", 14), ("dense-cf", 7),
                          ("dense-cf", 21), ("krylov-cf", 2), ("krylov-cf", 3)])
        with tempfile.TemporaryDirectory() as tmp:
            figure = Path(tmp) / make_benchmarks.SCALING_FIGURE
            md = "\n".join(make_benchmarks.scaling_section(write_scaling(Path(tmp) / "s.json", run), figure)[0])
            self.assertTrue(figure.is_file() or "Figure not drawn: matplotlib unavailable" in md)
        self.assertEqual(md.count("Paths marked -cf run the same networks with the fluid's face load lumped at the "
                                  "joint ends (`numerics.fluid_load: lumped`, the load work-conjugate to the lumped "
                                  "nodal volumes, design notes section 19) and frictionless fracture faces "
                                  "(`friction_angle: 0`, design notes section 31); the others with the seed's "
                                  "integrated face load and 30-degree friction."), 1)
        self.assertIn("count on the krylov paths only", md)
        self.assertIn("| dense-cf | 21 | 10,585 | 63,510 |", md)
        self.assertIn("| krylov-cf | 2 | 97 | 582 | 0.5 |", md)
        self.assertIn("- krylov-cf, 3 ribs (217 wetted nodes): over the time cap: warm-up step 1", md)
        self.assertIn("- dense-cf: Newton iterations per step 250 at 1,177 wetted nodes, 250 at 10,585; building S "
                      "took 38 % of the wall time per step at 10,585.", md)
        self.assertIn("- krylov: Newton iterations per step 250 at 1,177 wetted nodes, 250 at 4,705; 10 Krylov "
                      "iterations per Newton iteration at 4,705.", md)
        fits = ["| dense | 1.50 (2 sizes, 1,177-1,945) | 1.50 (2 sizes, 1,177-1,945) | 1.00 |",
                "| krylov | 1.10 (2 sizes, 1,177-4,705) | 1.10 (2 sizes, 1,177-4,705) | 1.00 |",
                "| dense-cf | 1.30 (2 sizes, 1,177-10,585) | 1.30 (2 sizes, 1,177-10,585) | 1.00 |",
                "| krylov-cf | not measured (fewer than 2 sizes) | not measured (fewer than 2 sizes) |  |"]
        times = ["- **dense: missed**: exponent 1.50 against 1.2 (2 sizes, 1,177 to 1,945 wetted nodes).",
                 "- **krylov: met up to 4,705 wetted nodes, not measured beyond**: exponent 1.10 against 1.2",
                 "- **dense-cf: missed**: exponent 1.30 against 1.2 (2 sizes, 1,177 to 10,585 wetted nodes).",
                 "- **krylov-cf: not met (not measured)**: no size with 1,000 or more wetted nodes ran"]
        memory = ["- **dense: not measured**: no size with 10,000 or more wetted nodes ran within the cap "
                  "(largest measured: 1,945 wetted nodes at 420 MB).",
                  "- **krylov: not measured**: no size with 10,000 or more wetted nodes ran within the cap "
                  "(largest measured: 4,705 wetted nodes at 900 MB).",
                  "- **dense-cf: met**: 10,585 wetted nodes peaked at 3,000 MB.",
                  "- **krylov-cf: not measured**: no size with 10,000 or more wetted nodes ran within the cap "
                  "(largest measured: 97 wetted nodes at 72 MB)."]
        for lines in (fits, times, memory):  # one line per path, in the order of the paths
            self.assertEqual([md.count(line) for line in lines], [1, 1, 1, 1])
            self.assertEqual(sorted(lines, key=md.index), lines)

    def test_augmented_paths_from_the_renamed_argument(self):
        # Rows named jacobian:2 are the augmented paths, reported after krylov and krylov-cf,
        # with their fits and verdicts (N^0.9 from 1,177 to 10,585 nodes in 3.4 GB: met).
        n = lambda ribs: 24 * ribs * ribs + 1  # noqa: E731
        run = [scaling_benchmark(7, 1, 1e-2 * n(7) ** 1.5, 200.0, cf=1),
               scaling_benchmark(14, 1, 1e-2 * n(14) ** 1.5, 900.0, cf=1),
               scaling_benchmark(7, 2, 1e-2 * n(7) ** 0.9, 500.0, cf=1),
               scaling_benchmark(21, 2, 1e-2 * n(21) ** 0.9, 3400.0, cf=1),
               scaling_benchmark(2, 2, 0.4, 80.0, cf=0)]
        rows = make_benchmarks.scaling_rows(run)
        self.assertEqual([(r["path"], r["ribs"]) for r in rows],
                         [("augmented", 2), ("krylov-cf", 7), ("krylov-cf", 14), ("augmented-cf", 7),
                          ("augmented-cf", 21)])
        with tempfile.TemporaryDirectory() as tmp:
            figure = Path(tmp) / make_benchmarks.SCALING_FIGURE
            md = "\n".join(make_benchmarks.scaling_section(write_scaling(Path(tmp) / "s.json", run), figure)[0])
        self.assertIn("- **augmented-cf: met**: exponent 0.90 against 1.2 (2 sizes, 1,177 to 10,585 wetted nodes).", md)
        self.assertIn("- **krylov-cf: missed**: exponent 1.50 against 1.2", md)
        self.assertIn("- **augmented-cf: met**: 10,585 wetted nodes peaked at 3,400 MB.", md)

    def test_old_runs_have_no_cf_path(self):
        # Names without conjugate_frictionless (the committed run): dense and krylov only, no -cf sentence.
        with tempfile.TemporaryDirectory() as tmp:
            md = "\n".join(make_benchmarks.scaling_section(write_scaling(Path(tmp) / "s.json", self.RUN), None)[0])
        self.assertEqual({r["path"] for r in make_benchmarks.scaling_rows(self.RUN)}, {"dense", "krylov"})
        self.assertNotIn("-cf", md)
        self.assertIn("count on the krylov path only", md)
        # A path without rows is left out: a dense-only run has no krylov line.
        with tempfile.TemporaryDirectory() as tmp:
            md = "\n".join(make_benchmarks.scaling_section(write_scaling(Path(tmp) / "s.json", self.RUN[:4]),
                                                           None)[0])
        self.assertIn("| dense | 1.50 (2 sizes, 1,177-1,945) |", md)
        self.assertNotIn("krylov:", md)
        self.assertNotIn("| krylov |", md)

    def test_section_rewritten_in_place_with_figure(self):
        with tempfile.TemporaryDirectory() as tmp:
            scaling = write_scaling(Path(tmp) / "network_scaling.json", self.RUN)
            out = Path(tmp) / "BENCHMARKS.md"
            out.write_text("# HFDDA benchmarks\n\n## bench_dda\n\nkept\n", encoding="utf-8")
            for _ in range(2):  # appended the first time, replaced the second
                p = subprocess.run([sys.executable, str(HERE / "make_benchmarks.py"), "--scaling", str(scaling),
                                    "--out", str(out)], capture_output=True, text=True, timeout=120)
                self.assertEqual(p.returncode, 0, p.stderr)
            md = out.read_text(encoding="utf-8")
            figure = Path(tmp) / make_benchmarks.SCALING_FIGURE
            try:
                import matplotlib  # noqa: F401
                self.assertTrue(figure.is_file())
                self.assertIn("![Network scaling](figures/network_scaling.png)", md)
            except ImportError:
                self.assertIn("Figure not drawn: matplotlib unavailable", md)
        self.assertTrue(md.startswith("# HFDDA benchmarks\n\n## bench_dda\n\nkept\n"))
        self.assertEqual(md.count("## Network scaling"), 1)
        self.assertEqual(md.count(make_benchmarks.SCALING_END), 1)

    def test_full_report_with_scaling_and_bad_file(self):
        results = HERE.parent / "benchmarks" / "testdata" / "run"
        with tempfile.TemporaryDirectory() as tmp:
            out = Path(tmp) / "BENCHMARKS.md"
            scaling = write_scaling(Path(tmp) / "network_scaling.json", self.RUN)
            self.assertEqual(make_benchmarks.write_report(results, out, scaling=scaling), 0)
            md = out.read_text(encoding="utf-8")
            self.assertLess(md.index("## Threads: 1 vs 2"), md.index("## Network scaling"))
            bad = Path(tmp) / "bad.json"
            bad.write_text("{", encoding="utf-8")
            self.assertEqual(make_benchmarks.update_scaling_section(bad, out), 1)
            self.assertIn("**Unreadable:** `bad.json`", out.read_text(encoding="utf-8"))


if __name__ == "__main__":
    unittest.main()
