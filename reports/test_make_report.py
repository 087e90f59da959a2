#!/usr/bin/python3
"""Tests of the report generators. Run: /usr/bin/python3 -m unittest reports/test_make_report.py
(or /usr/bin/python3 reports/test_make_report.py)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.dont_write_bytecode = True  # keep reports/ free of __pycache__
sys.path.insert(0, str(HERE))

import make_benchmarks  # noqa: E402
import make_report  # noqa: E402

PLOT_OK = """\
import json, sys
from pathlib import Path
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
case_dir = Path(sys.argv[1])
x = np.linspace(-1.0, 1.0, 21)
fig, ax = plt.subplots()
ax.plot(x, np.sqrt(1.0 - x**2))
fig.savefig(case_dir / "profile.png")
"""

PLOT_FAIL = "import sys\nsys.stderr.write('boom: no data\\n')\nsys.exit(3)\n"


def write_case(results: Path, name: str, data: dict) -> Path:
    d = results / name
    d.mkdir(parents=True)
    (d / "result.json").write_text(json.dumps(data), encoding="utf-8")
    return d


class MakeReportTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        root = Path(self.tmp.name)
        self.src, self.results, self.out = root / "src", root / "results", root / "out"
        for case, script in (("alpha", PLOT_OK), ("beta", PLOT_FAIL)):
            (self.src / "verification" / case).mkdir(parents=True)
            (self.src / "verification" / case / "plot.py").write_text(script, encoding="utf-8")
        self.results.mkdir()

    def tearDown(self):
        self.tmp.cleanup()

    def run_report(self):
        env = dict(os.environ, SOURCE_DATE_EPOCH="1700000000")
        return subprocess.run([sys.executable, str(HERE / "make_report.py"), "--results", str(self.results),
                               "--out", str(self.out), "--source-dir", str(self.src),
                               "--python", sys.executable],
                              capture_output=True, text=True, env=env, timeout=600)

    def add_two_cases(self):
        write_case(self.results, "alpha", {
            "case": "alpha", "title": "Griffith crack under constant pressure", "seed_section": "3.1",
            "tier": "quick", "status": "pass",
            "checks": [{"name": "tri4 ALM: max|w-w_exact| / w_peak", "value": 0.0123456, "threshold": 0.03,
                        "comparison": "<=", "expected": "pass", "passed": True, "note": "target"}],
            "metrics": {"blocks": 512, "error": {"l2": 0.00123456789, "max": 0.0123456}, "scheme": "ALM"},
            "figures": ["profile.png"], "notes": "Sneddon's *elliptical* profile."})
        write_case(self.results, "beta", {
            "case": "beta", "title": "Quadrilateral blocks", "seed_section": "3.1", "tier": "full",
            "status": "pass",
            "checks": [{"name": "quad ALM error", "value": 0.2, "threshold": 0.03, "comparison": "<=",
                        "expected": "fail", "passed": False, "note": "seed 3.1 reports quadrilaterals fail"},
                       {"name": "steps", "value": 10, "threshold": 5, "comparison": ">=",
                        "expected": "pass", "passed": True}],
            "metrics": {}, "figures": ["missing.png"], "notes": ""})
        (self.results / "gamma").mkdir()   # no result.json: not listed

    def test_report_content(self):
        self.add_two_cases()
        (self.out / "figures").mkdir(parents=True)
        (self.out / "figures" / "old_case_fig.png").write_bytes(b"stale")
        p = self.run_report()
        self.assertEqual(p.returncode, 0, p.stderr)
        md = (self.out / "VALIDATION.md").read_text(encoding="utf-8")

        self.assertIn("2023-11-14 22:13:20 UTC", md)
        self.assertRegex(md, r"- commit: `[^`]+`")
        self.assertIn("| [alpha](#case-alpha) | 3.1 | quick | ✅ pass | 1/1 | - | 1/1 |", md)
        self.assertIn("| [beta](#case-beta) | 3.1 | full | ✅ pass | 2/2 | - | 0/1 ⚠ plot failed |", md)
        self.assertIn("2 of 2 case results pass", md)
        self.assertNotIn("gamma", md)
        self.assertLess(md.index("## alpha"), md.index("## beta"))

        # checks table: escaped pipes, 4 significant digits, expected failure wording
        self.assertIn("tri4 ALM: max\\|w-w_exact\\| / w_peak | 0.01235 | <= 0.03 | pass | pass | ✅ | target |", md)
        self.assertIn("| quad ALM error | 0.2 | <= 0.03 | fail | expected failure (seed) | ✅ |", md)
        # metrics: dotted keys, 4 significant digits
        self.assertIn("| error.l2 | 0.001235 |", md)
        self.assertIn("| blocks | 512 |", md)
        self.assertIn("Sneddon's *elliptical* profile.", md)

        # figures: plot.py ran, figure copied and linked; failing plot and missing figure reported
        self.assertTrue((self.out / "figures" / "alpha_profile.png").is_file())
        self.assertIn("](figures/alpha_profile.png)", md)
        self.assertIn("**Plot failed:** plot.py exited with status 3", md)
        self.assertIn("boom: no data", md)
        self.assertIn("*Figure `missing.png` is missing.*", md)
        self.assertFalse((self.out / "figures" / "old_case_fig.png").exists())

    def test_mismatch_and_inconsistent_driver(self):
        write_case(self.results, "delta", {
            "case": "delta", "title": "D", "seed_section": "4.2", "tier": "quick", "status": "pass",
            "checks": [{"name": "mode I error", "value": 0.08, "threshold": 0.05, "comparison": "<=",
                        "expected": "pass", "passed": False}],
            "metrics": {}, "figures": []})
        write_case(self.results, "eps", {
            "case": "eps", "title": "E", "seed_section": "4.3", "tier": "quick", "status": "pass",
            "checks": [{"name": "lying check", "value": 0.5, "threshold": 0.1, "comparison": "<=",
                        "expected": "pass", "passed": True}]})
        (self.results / "zeta").mkdir()
        (self.results / "zeta" / "result.json").write_text("{not json", encoding="utf-8")
        p = self.run_report()
        self.assertEqual(p.returncode, 0, p.stderr)
        md = (self.out / "VALIDATION.md").read_text(encoding="utf-8")
        self.assertIn("| [delta](#case-delta) | 4.2 | quick | ❌ **fail (driver says pass)** | 0/1 | - | none |", md)
        self.assertIn("| **FAIL** | ❌ **no** |", md)
        self.assertIn("driver says pass but value <= threshold gives fail", md)
        self.assertIn("❌ **error**", md)
        self.assertIn("unreadable result.json", md)
        self.assertIn("0 of 3 case results pass", md)

    def test_junit_failures_listed(self):
        self.add_two_cases()
        junit = Path(self.tmp.name) / "junit.xml"
        junit.write_text(
            '<?xml version="1.0" encoding="UTF-8"?>\n<testsuite tests="3" failures="1">\n'
            '<testcase name="alpha_quick" status="run"><system-out/></testcase>\n'
            '<testcase name="beta_full" status="run"><system-out/></testcase>\n'
            '<testcase name="crashing_full" status="fail"><failure message=""/></testcase>\n'
            '</testsuite>\n', encoding="utf-8")
        env = dict(os.environ, SOURCE_DATE_EPOCH="1700000000")
        p = subprocess.run([sys.executable, str(HERE / "make_report.py"), "--results", str(self.results),
                            "--out", str(self.out), "--source-dir", str(self.src), "--python", sys.executable,
                            "--junit", str(junit)], capture_output=True, text=True, env=env, timeout=600)
        self.assertEqual(p.returncode, 0, p.stderr)
        md = (self.out / "VALIDATION.md").read_text(encoding="utf-8")
        self.assertIn("- ctest: 2 of 3 tests passed", md)
        self.assertIn("| crashing_full | ❌ failed |", md)

    def test_no_results(self):
        p = self.run_report()
        self.assertEqual(p.returncode, 1)
        md = (self.out / "VALIDATION.md").read_text(encoding="utf-8")
        self.assertIn("No verification results found", md)

    def test_helpers(self):
        self.assertEqual(make_report.fmt_value(1234567.8), "1.235e+06")
        self.assertEqual(make_report.fmt_value(10000.0), "10000")
        self.assertEqual(make_report.fmt_value(True), "true")
        self.assertEqual(make_report.fmt_value(list(range(20))), "[20 values, 0 .. 19]")
        self.assertEqual(make_report.flatten({"a": {"b": 1, "c": {"d": 2}}, "e": 3}),
                         [("a.b", 1), ("a.c.d", 2), ("e", 3)])
        ev = make_report.evaluate_check({"value": 0.2, "threshold": 0.03, "comparison": "<=",
                                         "expected": "fail", "passed": False})
        self.assertTrue(ev["matches"])
        self.assertEqual(ev["outcome"], "expected failure (seed)")
        ev = make_report.evaluate_check({"value": 0.01, "threshold": 0.03, "comparison": "<=",
                                         "expected": "fail", "passed": True})
        self.assertFalse(ev["matches"])
        self.assertEqual(ev["outcome"], "unexpected pass")


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


if __name__ == "__main__":
    unittest.main()
