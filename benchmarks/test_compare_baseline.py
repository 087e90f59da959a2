#!/usr/bin/python3
"""Tests of compare_baseline.py on the fixtures in testdata/ (a stored baseline and one
binary's Google Benchmark output). Run: /usr/bin/python3 benchmarks/test_compare_baseline.py"""

from __future__ import annotations

import copy
import io
import json
import subprocess
import sys
import tempfile
import unittest
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.dont_write_bytecode = True  # keep benchmarks/ free of __pycache__
sys.path.insert(0, str(HERE))

import compare_baseline as cb  # noqa: E402

DATA = HERE / "testdata"
RUN = json.loads((DATA / "run" / "bench_small.json").read_text(encoding="utf-8"))
BASELINE = json.loads((DATA / "baseline.json").read_text(encoding="utf-8"))
STEP = "bench_small:BM_Step/cells:16/threads:1"
NOISY = "bench_small:BM_Noisy"


def scaled(run: dict, factor: float, prefix: str = "", calibration: bool = False) -> dict:
    """The run with the times of the benchmarks whose name starts with prefix times factor,
    and with calibration, the calibration timed next to them too (a slower machine)."""
    out = copy.deepcopy(run)
    for b in out["benchmarks"]:
        if b["run_name"].startswith(prefix):
            b["real_time"] *= factor
            b["cpu_time"] *= factor
            if calibration and "calibration_real_ms" in b:
                b["calibration_real_ms"] *= factor
                b["calibration_cpu_ms"] *= factor
    return out


def without_adjacent_calibration(run: dict) -> dict:
    out = copy.deepcopy(run)
    for b in out["benchmarks"]:
        b.pop("calibration_real_ms", None)
        b.pop("calibration_cpu_ms", None)
    return out


class CompareBaselineTest(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory()
        self.tmp = Path(self._tmp.name)

    def tearDown(self):
        self._tmp.cleanup()

    def results(self, run: dict) -> Path:
        d = self.tmp / "results"
        d.mkdir(exist_ok=True)
        (d / "bench_small.json").write_text(json.dumps(run), encoding="utf-8")
        return d

    def compare(self, run: dict, baseline: dict = BASELINE) -> tuple[dict, list[str]]:
        rows, warnings = cb.compare(baseline, cb.load_run(self.results(run)))
        return {r["benchmark"]: r for r in rows}, warnings

    def cli(self, run: dict, baseline: Path = DATA / "baseline.json") -> subprocess.CompletedProcess:
        """main() as the command line runs it, in this process (a subprocess each costs 0.1 s)."""
        args = ["--results", str(self.results(run)), "--baseline", str(baseline), "--markdown", str(self.tmp / "cmp.md")]
        out, err = io.StringIO(), io.StringIO()
        with redirect_stdout(out), redirect_stderr(err):
            rc = cb.main(args)
        return subprocess.CompletedProcess(args, rc, out.getvalue(), err.getvalue())

    def test_command_line(self):
        p = subprocess.run([sys.executable, str(HERE / "compare_baseline.py"), "--results",
                            str(self.results(scaled(RUN, 1.3, "BM_Noisy"))), "--baseline", str(DATA / "baseline.json")],
                           capture_output=True, text=True, timeout=60)
        self.assertEqual(p.returncode, 1, p.stdout + p.stderr)
        self.assertRegex(p.stdout, r"bench_small:BM_Noisy +20\.1 +26 +1\.29 +1\.29 +4\.3 % +1\.13 +slower")

    def test_run_statistics(self):
        run = cb.load_run(self.results(RUN))
        step = run["benchmarks"][STEP]
        self.assertEqual(step["repetitions"], 5)  # repetitions only, not the median aggregate
        self.assertAlmostEqual(step["real"]["median_ms"], 10.0)
        self.assertAlmostEqual(step["real"]["noise"], 1.4826 * 0.05 / 10.0)
        self.assertAlmostEqual(step["real"]["normalised"], 2.0)  # by BM_Calibration's median
        self.assertAlmostEqual(step["real"]["adjacent"], 2.0)  # repetition by repetition
        # Ratios 4.0, 4.198, 3.798, 4.1, 3.884: median 4.0, median absolute deviation 4.0 - 19.5 / 5.02.
        self.assertAlmostEqual(run["benchmarks"][NOISY]["real"]["adjacent_noise"], 1.4826 * (4.0 - 19.5 / 5.02) / 4.0)
        self.assertAlmostEqual(run["benchmarks"]["bench_small:BM_Long"]["real"]["median_ms"], 1000.0)  # s -> ms
        self.assertEqual(run["host"]["cpu_model"], "Test CPU @ 2.00GHz")

    def test_unchanged_run_passes(self):
        rows, warnings = self.compare(RUN)
        self.assertEqual(warnings, [])
        self.assertEqual(rows["bench_small:BM_Calibration"]["verdict"], "reference")
        self.assertEqual({r["verdict"] for k, r in rows.items() if "Calibration" not in k}, {"ok"})
        p = self.cli(RUN)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        self.assertIn("0 slower", p.stdout)
        md = (self.tmp / "cmp.md").read_text(encoding="utf-8")
        # CPU time by default (baseline 9.82 ms), wall time on request (10.02 ms).
        self.assertIn("| bench_small:BM_Step/cells:16/threads:1 | 9.82 | 9.8 | 0.998 | 0.998 | 0.8 % | 1.05 | ok |",
                      md)
        rows, _ = cb.compare(BASELINE, cb.load_run(self.results(RUN)), metric="real")
        self.assertEqual(rows[1]["benchmark"], STEP)
        self.assertAlmostEqual(rows[1]["baseline_ms"], 10.02)

    def test_30_percent_slower_is_flagged(self):
        run = scaled(RUN, 1.3, "BM_Step/cells:16/threads:1/")
        rows, _ = self.compare(run)
        self.assertEqual(rows[STEP]["verdict"], "slower")
        self.assertAlmostEqual(rows[STEP]["normalised_ratio"], 1.3, places=2)
        self.assertEqual(rows["bench_small:BM_Step/cells:16/threads:2"]["verdict"], "ok")
        p = self.cli(run)
        self.assertEqual(p.returncode, 1, p.stdout + p.stderr)
        self.assertIn(f"1 slower: {STEP}", p.stdout)
        # Even on the noisiest benchmark of the fixture (4 % spread).
        self.assertEqual(self.compare(scaled(RUN, 1.3, "BM_Noisy"))[0][NOISY]["verdict"], "slower")

    def test_change_within_noise_is_not_flagged(self):
        rows, _ = self.compare(scaled(RUN, 1.08, "BM_Noisy"))
        self.assertEqual(rows[NOISY]["verdict"], "ok")  # limit 1 + 3 x 4 % spread
        self.assertGreater(rows[NOISY]["limit"], 1.1)
        # The same 8 % on a quiet benchmark exceeds its limit (the 5 % floor) ...
        self.assertEqual(self.compare(scaled(RUN, 1.08, "BM_Step/cells:16/threads:1/"))[0][STEP]["verdict"], "slower")
        # ... and 3 % does not.
        self.assertEqual(self.compare(scaled(RUN, 1.03, "BM_Step/cells:16/threads:1/"))[0][STEP]["verdict"], "ok")
        # Normalised by BM_Calibration (another host, no adjacent calibration), the
        # calibration's noise widens the limit too.
        run = scaled(without_adjacent_calibration(RUN), 1.08, "BM_Step/cells:16/threads:1/")
        run["context"]["cpu_model"] = "Other CPU"
        self.assertEqual(self.compare(run)[0][STEP]["verdict"], "slower")
        noisy_calibration = copy.deepcopy(BASELINE)
        for metric in cb.METRICS:
            noisy_calibration["benchmarks"]["bench_small:BM_Calibration"][metric]["noise"] = 0.04
        rows, _ = self.compare(run, noisy_calibration)
        self.assertEqual((rows[STEP]["basis"], rows[STEP]["verdict"]), ("normalised by run", "ok"))
        # Faster beyond the limit is reported, not failed.
        rows, _ = self.compare(scaled(RUN, 0.7, "BM_Step/cells:16/threads:1/"))
        self.assertEqual(rows[STEP]["verdict"], "faster")
        self.assertFalse(cb.failed(list(rows.values())))

    def test_slower_machine_is_not_a_regression(self):
        rows, _ = self.compare(scaled(RUN, 1.25, calibration=True))
        self.assertAlmostEqual(rows[STEP]["ratio"], 1.25, places=2)
        self.assertAlmostEqual(rows[STEP]["normalised_ratio"], 1.0, places=2)
        self.assertEqual({r["verdict"] for k, r in rows.items() if "Calibration" not in k}, {"ok"})
        # Without a calibration next to it, the same host compares absolute times.
        rows, _ = self.compare(without_adjacent_calibration(scaled(RUN, 1.25, calibration=True)))
        self.assertEqual((rows[STEP]["basis"], rows[STEP]["verdict"]), ("absolute", "slower"))

    def test_missing_and_new_benchmarks_are_reported(self):
        run = copy.deepcopy(RUN)
        run["benchmarks"] = [b for b in run["benchmarks"] if not b["run_name"].startswith("BM_Long")]
        for b in run["benchmarks"]:
            if b["run_name"].startswith("BM_Noisy"):
                b["run_name"] = b["name"] = "BM_Added/real_time"
        rows, _ = self.compare(run)
        self.assertEqual(rows["bench_small:BM_Long"]["verdict"], "not run")
        self.assertEqual(rows[NOISY]["verdict"], "not run")
        self.assertEqual(rows["bench_small:BM_Added"]["verdict"], "new")
        p = self.cli(run)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        self.assertIn("2 of the baseline's benchmarks not run: bench_small:BM_Noisy, bench_small:BM_Long", p.stdout)
        self.assertRegex(p.stdout, r"bench_small:BM_Added +20 +new")

    def test_host_mismatch_warns_and_compares_normalised(self):
        run = scaled(RUN, 2.0, calibration=True)  # a host half as fast
        run["context"]["cpu_model"] = "Other CPU"
        rows, warnings = self.compare(run)
        self.assertEqual(len(warnings), 1)
        self.assertIn("host differs", warnings[0])
        self.assertEqual((rows[STEP]["basis"], rows[STEP]["verdict"]), ("normalised", "ok"))
        p = self.cli(scaled(run, 1.3, "BM_Step/cells:16/threads:1/"))
        self.assertEqual(p.returncode, 1)
        self.assertIn("host differs", p.stderr)
        self.assertIn("host differs", (self.tmp / "cmp.md").read_text(encoding="utf-8"))
        # Without any calibration nothing can be compared on another host.
        run = without_adjacent_calibration(run)
        run["benchmarks"] = [b for b in run["benchmarks"] if not b["run_name"].startswith("BM_Calibration")]
        rows, _ = self.compare(run)
        self.assertEqual(rows[STEP]["verdict"], "not compared (no calibration)")

    def test_failed_benchmark_fails_the_comparison(self):
        run = copy.deepcopy(RUN)
        for b in run["benchmarks"]:
            if b["run_name"].startswith("BM_Long"):
                b.update(error_occurred=True, error_message="diverged")
        rows, _ = self.compare(run)
        self.assertEqual(rows["bench_small:BM_Long"]["verdict"], "error: diverged")
        self.assertTrue(cb.failed(list(rows.values())))

    def test_saved_baseline_compares_equal(self):
        out = self.tmp / "baseline.json"
        with redirect_stdout(io.StringIO()):
            self.assertEqual(cb.main(["--results", str(self.results(RUN)), "--save", str(out), "--note", "t"]), 0)
        saved = json.loads(out.read_text(encoding="utf-8"))
        self.assertEqual(saved["host"]["num_cpus"], 2)
        self.assertTrue(saved["commit"])
        self.assertEqual(saved["benchmarks"][STEP]["repetitions"], 5)
        rows, _ = self.compare(RUN, saved)
        self.assertEqual({r["verdict"] for k, r in rows.items() if "Calibration" not in k}, {"ok"})
        self.assertEqual({r["normalised_ratio"] for k, r in rows.items() if "Calibration" not in k}, {1.0})

    def test_without_baseline_nothing_fails(self):
        err = io.StringIO()
        with redirect_stderr(err):
            rc = cb.main(["--results", str(self.results(RUN)), "--baseline", str(self.tmp / "none.json")])
        self.assertEqual(rc, 0)
        self.assertIn("no baseline", err.getvalue())


if __name__ == "__main__":
    unittest.main()
