#!/usr/bin/python3
"""Tests of the report generators. Run: cd reports && /usr/bin/python3 -m unittest test_make_report
(or /usr/bin/python3 reports/test_make_report.py)."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path
from unittest import mock

HERE = Path(__file__).resolve().parent
sys.dont_write_bytecode = True  # keep reports/ free of __pycache__
sys.path.insert(0, str(HERE))

import make_benchmarks  # noqa: E402
import make_report  # noqa: E402
import source_state  # noqa: E402

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


def check(name, value, threshold, comparison="<=", expected="pass", passed=None, gating=True, note=""):
    """A check as the harness writes it (passed computed unless given)."""
    if passed is None:
        passed = make_report.recompute_passed({"value": value, "threshold": threshold, "comparison": comparison})
    return {"name": name, "value": value, "threshold": threshold, "comparison": comparison,
            "expected": expected, "passed": passed, "gating": gating, "note": note}


def griffith_like(tier: str) -> dict:
    """Gating checks (one an expected failure of the seed) and reported-only ones, one missed."""
    return {
        "case": "alpha", "title": "Griffith crack under constant pressure", "seed_section": "3.1",
        "tier": tier, "status": "fail", "wall_s": 12.0,
        "checks": [check("tri4 ALM: max|w-w_exact| / w_peak", 0.0123456, 0.03, note="target"),
                   check("quad ALM error", 0.2, 0.03, expected="fail", note="seed 3.1: quadrilaterals fail"),
                   check("vertex-vertex contacts", 0, 0),
                   check("seed geometry error", 0.0377, 0.03, gating=False, note="finite domain"),
                   check("error ratio", 0.7, 1.0, gating=False)],
        "metrics": {"blocks": 512}, "figures": [], "notes": ""}


def kgd_like(tier: str, gating_miss: bool) -> dict:
    return {
        "case": "beta", "title": "KGD viscosity-storage fracture (M-vertex)", "seed_section": "3.2",
        "tier": tier, "status": "fail" if gating_miss else "pass",
        "checks": [check("dx = 2 m: run completed", 1.0, 1.0, "=="),
                   check("dx = 2 m: width error", 0.08 if gating_miss else 0.02, 0.05),
                   check("width error in band", 0.5, [0.0, 1.0], "in", gating=False)],
        "metrics": {}, "figures": [], "notes": ""}


README_TEXT = """# Project

Intro paragraph.

<!-- verified-summary:begin -->
Hand-written text that the generator replaces.
<!-- verified-summary:end -->

## Next section

Kept as it is.
"""


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

    def run_report(self, *extra, env_extra=None):
        env = dict(os.environ, SOURCE_DATE_EPOCH="1700000000", **(env_extra or {}))
        return subprocess.run([sys.executable, str(HERE / "make_report.py"), "--results", str(self.results),
                               "--out", str(self.out), "--source-dir", str(self.src),
                               "--python", sys.executable, *extra],
                              capture_output=True, text=True, env=env, timeout=600)

    def report(self, *extra) -> str:
        p = self.run_report(*extra)
        self.assertEqual(p.returncode, 0, p.stderr)
        return (self.out / "VALIDATION.md").read_text(encoding="utf-8")

    def add_two_cases(self):
        write_case(self.results, "alpha", {
            "case": "alpha", "title": "Griffith crack under constant pressure", "seed_section": "3.1",
            "tier": "quick", "status": "pass",
            "checks": [check("tri4 ALM: max|w-w_exact| / w_peak", 0.0123456, 0.03, note="target")],
            "metrics": {"blocks": 512, "error": {"l2": 0.00123456789, "max": 0.0123456}, "scheme": "ALM"},
            "figures": ["profile.png"], "notes": "Sneddon's *elliptical* profile."})
        write_case(self.results, "beta", {
            "case": "beta", "title": "Quadrilateral blocks", "seed_section": "3.1", "tier": "full",
            "status": "pass",
            "checks": [check("quad ALM error", 0.2, 0.03, expected="fail",
                             note="seed 3.1 reports quadrilaterals fail"),
                       check("steps", 10, 5, ">=", gating=False)],
            "metrics": {}, "figures": ["missing.png"], "notes": ""})
        (self.results / "gamma").mkdir()   # no result.json: not listed

    def test_report_content(self):
        self.add_two_cases()
        (self.out / "figures").mkdir(parents=True)
        (self.out / "figures" / "old_case_fig.png").write_bytes(b"stale")
        # The benchmark report's figure lives in the same folder and is not the case report's to drop.
        (self.out / "figures" / "network_scaling.png").write_bytes(b"benchmark")
        (self.out / "BENCHMARKS.md").write_text("![Network scaling](figures/network_scaling.png)\n")
        md = self.report()

        self.assertIn("2023-11-14 22:13:20 UTC", md)
        self.assertIn("- commit: ", md)
        self.assertIn("| case | seed section | tier | gating checks | reported only | run time | figures |", md)
        self.assertIn("| [alpha](#case-alpha) | 3.1 | quick | ✅ 1/1 as expected | none | - | 1/1 |", md)
        self.assertIn("| [beta](#case-beta) | 3.1 | full | ✅ 1/1 as expected (1 expected failure) "
                      "| ✅ 1/1 as expected | - | 0/1 ⚠ plot failed |", md)
        self.assertIn("2 of 2 case results meet every gating check", md)
        self.assertIn("2 of 2 have every check as expected", md)
        self.assertNotIn("gamma", md)
        self.assertLess(md.index("## alpha"), md.index("## beta"))

        # checks table: gating column, escaped pipes, 4 significant digits, expected failure wording
        self.assertIn("| check | gating | value | criterion | expected | outcome | as expected | note |", md)
        self.assertIn("| tri4 ALM: max\\|w-w_exact\\| / w_peak | **yes** | 0.01235 | <= 0.03 | pass | pass "
                      "| ✅ | target |", md)
        self.assertIn("| quad ALM error | **yes** | 0.2 | <= 0.03 | fail | expected failure (seed) | ✅ |", md)
        self.assertIn("| steps | no | 10 | >= 5 | pass | pass | ✅ |  |", md)
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
        self.assertTrue((self.out / "figures" / "network_scaling.png").exists())

    def test_blas_kernels_stated_and_mixed_ones_flagged(self):
        self.add_two_cases()
        md = self.report()
        self.assertIn("- BLAS kernels: not recorded for every result;", md)
        for name, kernels in (("alpha", "Haswell"), ("beta", "Haswell")):
            data = json.loads((self.results / name / "result.json").read_text())
            data["environment"] = {"threads": 1, "blas_kernels": kernels}
            (self.results / name / "result.json").write_text(json.dumps(data))
        md = self.report()
        self.assertIn("- BLAS kernels: Haswell for every result;", md)
        self.assertLess(md.index("- produced by"), md.index("- BLAS kernels"))
        data = json.loads((self.results / "beta" / "result.json").read_text())
        data["environment"]["blas_kernels"] = "Cooperlake"
        (self.results / "beta" / "result.json").write_text(json.dumps(data))
        md = self.report()
        self.assertIn("- BLAS kernels: **mixed**: Cooperlake (`beta`); Haswell (`alpha`);", md)

    def test_gating_counted_apart_from_reported_only(self):
        write_case(self.results, "alpha", griffith_like("full"))
        write_case(self.results, "beta", kgd_like("full", gating_miss=True))
        md = self.report()
        # alpha: every gating check as expected, one of them an expected failure; a reported-only miss
        self.assertIn("| [alpha](#case-alpha) | 3.1 | full | ✅ 3/3 as expected (1 expected failure) "
                      "| ⚠ 1/2 as expected | 12 s | none |", md)
        self.assertIn("seed section 3.1 · tier full · gating checks: ✅ 3/3 as expected (1 expected failure)"
                      " · reported only: ⚠ 1/2 as expected", md)
        self.assertIn("| seed geometry error | no | 0.0377 | <= 0.03 | pass | **FAIL** | ⚠ no (reported only) "
                      "| finite domain |", md)
        self.assertIn("| error ratio | no | 0.7 | <= 1 | pass | pass | ✅ |", md)
        # beta: a gating miss
        self.assertIn("| [beta](#case-beta) | 3.2 | full | ❌ **1/2 as expected** | ✅ 1/1 as expected |", md)
        self.assertIn("| dx = 2 m: width error | **yes** | 0.08 | <= 0.05 | pass | **FAIL** | ❌ **no** |", md)
        self.assertIn("| width error in band | no | 0.5 | in [0, 1] | pass | pass | ✅ |", md)
        self.assertIn("1 of 2 case results meet every gating check", md)
        self.assertIn("0 of 2 have every check as expected", md)

    def test_expected_failure_distinct_from_pass(self):
        write_case(self.results, "alpha", {
            "case": "alpha", "title": "A", "seed_section": "3.1", "tier": "full", "status": "fail",
            "checks": [check("fails as the seed says", 0.9, 0.03, expected="fail"),
                       check("passes", 0.01, 0.03),
                       check("seed says fail, passes", 0.01, 0.03, expected="fail", gating=False)]})
        md = self.report()
        self.assertIn("| fails as the seed says | **yes** | 0.9 | <= 0.03 | fail | expected failure (seed) | ✅ |", md)
        self.assertIn("| passes | **yes** | 0.01 | <= 0.03 | pass | pass | ✅ |", md)
        self.assertIn("| seed says fail, passes | no | 0.01 | <= 0.03 | fail | unexpected pass "
                      "| ⚠ no (reported only) |", md)
        self.assertIn("✅ 2/2 as expected (1 expected failure) | ⚠ 0/1 as expected (1 expected failure)", md)

    def test_expected_failure_without_a_value_is_a_failure(self):
        # A run that crashed or gave NaN is not "fails as in the seed": the harness says
        # as_expected false, and a missing value alone is enough when it does not.
        nan_check = check("crashed quadrilateral run", None, 0.03, expected="fail", passed=False)
        nan_check["as_expected"] = False
        old_driver = check("no value, old driver", None, 0.03, expected="fail", passed=False)
        old_driver.pop("as_expected", None)
        write_case(self.results, "theta", {
            "case": "theta", "title": "T", "seed_section": "3.1", "tier": "full", "status": "fail",
            "checks": [nan_check, old_driver]})
        md = self.report()
        self.assertNotIn("expected failure (seed)", md)
        self.assertIn("| crashed quadrilateral run | **yes** | n/a | <= 0.03 | fail | **FAIL** (no value or no "
                      "completed run) | ❌ **no** |", md)
        self.assertIn("❌ **0/2 as expected", md)

    def test_mismatch_and_inconsistent_driver(self):
        write_case(self.results, "delta", {
            "case": "delta", "title": "D", "seed_section": "4.2", "tier": "quick", "status": "fail",
            "checks": [check("mode I error", 0.08, 0.05)], "metrics": {}, "figures": []})
        write_case(self.results, "eps", {
            "case": "eps", "title": "E", "seed_section": "4.3", "tier": "quick", "status": "pass",
            "checks": [check("lying check", 0.5, 0.1, passed=True)]})
        write_case(self.results, "eta", {   # no gating flag: counted as gating, and said so
            "case": "eta", "title": "H", "seed_section": "4.4", "tier": "quick", "status": "pass",
            "checks": [{"name": "old driver", "value": 1.0, "threshold": 2.0, "comparison": "<=",
                        "expected": "pass", "passed": True}]})
        (self.results / "zeta").mkdir()
        (self.results / "zeta" / "result.json").write_text("{not json", encoding="utf-8")
        md = self.report()
        self.assertIn("| [delta](#case-delta) | 4.2 | quick | ❌ **0/1 as expected** | none | - | none |", md)
        self.assertIn("| **FAIL** | ❌ **no** |", md)
        self.assertIn("| [eps](#case-eps) | 4.3 | quick | ❌ **0/1 as expected; driver says pass** |", md)
        self.assertIn("driver says pass but value <= threshold gives fail", md)
        self.assertIn("| old driver | **yes** | 1 | <= 2 | pass | pass | ✅ | ⚠ no gating flag recorded: "
                      "counted as gating |", md)
        self.assertIn("| [zeta](#case-zeta) |  |  | ❌ **error** | none |", md)
        self.assertIn("unreadable result.json", md)
        self.assertIn("1 of 4 case results meet every gating check", md)

    def test_junit_failures_listed(self):
        self.add_two_cases()
        junit = Path(self.tmp.name) / "junit.xml"
        junit.write_text(
            '<?xml version="1.0" encoding="UTF-8"?>\n<testsuite tests="3" failures="1">\n'
            '<testcase name="alpha_quick" status="run"><system-out/></testcase>\n'
            '<testcase name="beta_full" status="run"><system-out/></testcase>\n'
            '<testcase name="crashing_full" status="fail"><failure message=""/></testcase>\n'
            '</testsuite>\n', encoding="utf-8")
        md = self.report("--junit", str(junit))
        self.assertIn("- ctest: 2 of 3 tests passed", md)
        self.assertIn("| crashing_full | ❌ failed |", md)

    def test_no_results(self):
        p = self.run_report()
        self.assertEqual(p.returncode, 1)
        md = (self.out / "VALIDATION.md").read_text(encoding="utf-8")
        self.assertIn("No verification results found", md)

    # ------------------------------------------------------------------ README section
    def readme_setup(self) -> Path:
        for case in ("alpha", "beta"):
            (self.src / "verification" / case / "study.yaml").write_text(f"case: {case}\n", encoding="utf-8")
        (self.src / "verification" / "alpha" / "README.md").write_text("# alpha\n", encoding="utf-8")
        readme = self.src / "README.md"
        readme.write_text(README_TEXT, encoding="utf-8")
        return readme

    def test_readme_section_from_full_tier(self):
        readme = self.readme_setup()
        write_case(self.results, "alpha", griffith_like("full"))
        write_case(self.results, "alpha-quick", griffith_like("quick"))
        write_case(self.results, "beta", kgd_like("full", gating_miss=True))
        md = self.report("--readme", str(readme))
        self.assertIn("- README summary: `README.md` section regenerated from the full-tier results", md)
        text = readme.read_text(encoding="utf-8")
        before, section, after = source_state.split_readme(text)
        self.assertEqual(before + after, README_TEXT.replace("Hand-written text that the generator replaces.\n",
                                                             ""))
        self.assertNotIn("Hand-written", text)
        lines = section.splitlines()
        self.assertTrue(lines[0].startswith("<!-- Written by reports/make_report.py from the full verification"))
        self.assertIn("Verified so far (seed chapter 3): the full verification tier at an unknown commit", lines[1])
        self.assertIn(", 2023-11-14. Every check is in [`../out/VALIDATION.md`](../out/VALIDATION.md); cases, "
                      "tiers and times in [`verification/README.md`](verification/README.md).", lines[1])
        self.assertIn("1 of 2 cases meet every gating check.", lines[1])
        # one line per case, full tier only, by seed section; the first miss, gating before reported-only
        self.assertEqual(lines[2:], [
            "- Griffith crack under constant pressure (3.1): gating 3/3 as expected (1 expected failure); "
            "reported only 1/2 as expected; first miss (reported only): `seed geometry error` is 0.0377, "
            "criterion <= 0.03, expected pass "
            "([`verification/alpha/README.md`](verification/alpha/README.md)).",
            "- KGD viscosity-storage fracture (M-vertex) (3.2): gating 1/2 as expected; reported only 1/1 as "
            "expected; first miss (gating): `dx = 2 m: width error` is 0.08, criterion <= 0.05, expected pass."])

        # A second run with the same results leaves the file as it is.
        md = self.report("--readme", str(readme))
        self.assertIn("section regenerated from the full-tier results (unchanged)", md)
        self.assertEqual(readme.read_text(encoding="utf-8"), text)

    def test_readme_untouched_on_partial_results(self):
        readme = self.readme_setup()
        write_case(self.results, "alpha-quick", griffith_like("quick"))
        write_case(self.results, "beta-quick", kgd_like("quick", gating_miss=False))
        md = self.report("--readme", str(readme))
        self.assertIn("- README summary: not updated: partial results, no full-tier result for `alpha`, `beta`", md)
        self.assertEqual(readme.read_text(encoding="utf-8"), README_TEXT)
        # One full case of two (e.g. `scripts/verify -R alpha`) is still partial.
        write_case(self.results, "alpha", griffith_like("full"))
        md = self.report("--readme", str(readme))
        self.assertIn("no full-tier result for `beta`", md)
        self.assertEqual(readme.read_text(encoding="utf-8"), README_TEXT)

    def test_readme_bad_markers(self):
        readme = self.readme_setup()
        bad = README_TEXT.replace("<!-- verified-summary:end -->\n", "")
        readme.write_text(bad, encoding="utf-8")
        write_case(self.results, "alpha", griffith_like("full"))
        write_case(self.results, "beta", kgd_like("full", gating_miss=False))
        p = self.run_report("--readme", str(readme))
        self.assertEqual(p.returncode, 1)
        self.assertIn("README.md: marker lines '<!-- verified-summary:begin -->' and "
                      "'<!-- verified-summary:end -->' must each appear exactly once", p.stderr)
        self.assertIn("found 1 and 0", p.stderr)
        self.assertEqual(readme.read_text(encoding="utf-8"), bad)
        self.assertTrue((self.out / "VALIDATION.md").is_file())   # the report is still written
        with self.assertRaisesRegex(ValueError, r"R:6: marker lines .* \(found 2 and 1\)"):
            source_state.split_readme(README_TEXT.replace("Hand-written", source_state.README_BEGIN + "\nHand"), "R")
        with self.assertRaisesRegex(ValueError, r"R:8: '<!-- verified-summary:end -->' comes before"):
            source_state.split_readme("text\n" * 7 + source_state.README_END + "\n" + source_state.README_BEGIN + "\n",
                                     "R")

    def test_project_readme_has_markers(self):
        """scripts/verify rewrites this section: the markers must be usable."""
        text = (HERE.parent / "README.md").read_text(encoding="utf-8")
        before, section, after = source_state.split_readme(text)
        self.assertIn("## Two commands", after)

    # ------------------------------------------------------------------ provenance
    def test_provenance_with_git(self):
        if shutil.which("git") is None:
            self.skipTest("git not installed")
        self.add_two_cases()
        readme = self.readme_setup()
        g = ["git", "-C", str(self.src), "-c", "user.name=t", "-c", "user.email=t@example.org"]
        subprocess.run(g + ["init", "-q"], check=True)
        (self.src / ".gitignore").write_text("/build/\n", encoding="utf-8")
        subprocess.run(g + ["add", "-A"], check=True)
        subprocess.run(g + ["commit", "-q", "-m", "fixture"], check=True)
        head = subprocess.run(g + ["rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                              check=True).stdout.strip()
        # The report's own output inside the tree, build dirs and an untracked results dir do not count.
        self.out = self.src / "reports"
        (self.src / "build-debug").mkdir()
        (self.src / "build-debug" / "x.o").write_bytes(b"")
        md = self.report()
        self.assertIn(f"- commit: `{head}`; working tree clean (the report's own files and build "
                      "directories not counted)", md)
        # A README changed only inside its generated section still counts as clean ...
        readme.write_text(README_TEXT.replace("Hand-written", "Regenerated"), encoding="utf-8")
        md = self.report()
        self.assertIn(f"- commit: `{head}`; working tree clean", md)
        # ... a change anywhere else does not.
        readme.write_text(README_TEXT + "edited\n", encoding="utf-8")
        (self.src / "verification" / "alpha" / "plot.py").write_text(PLOT_OK + "# edit\n", encoding="utf-8")
        md = self.report("--readme", str(readme))
        self.assertIn(f"- commit: `{head}`; working tree **not clean**: 2 uncommitted paths "
                      "(`README.md`, `verification/alpha/plot.py`)", md)

    def test_provenance_without_git(self):
        self.add_two_cases()
        empty = Path(self.tmp.name) / "empty-path"
        empty.mkdir()
        p = self.run_report(env_extra={"PATH": str(empty)})
        self.assertEqual(p.returncode, 0, p.stderr)
        md = (self.out / "VALIDATION.md").read_text(encoding="utf-8")
        self.assertIn("- commit: unknown: git is not installed; whether the working tree was clean is unknown", md)

    def test_provenance_mock_git(self):
        """git_state on canned git output: clean, dirty (with a rename and paths that do not count),
        not a repository."""
        top = Path(self.tmp.name) / "repo"
        (top / "reports").mkdir(parents=True)
        readme = top / "README.md"
        readme.write_text(README_TEXT.replace("Hand-written", "Regenerated"), encoding="utf-8")

        def fake(status):
            def git(source_dir, *args):
                if args[:2] == ("rev-parse", "--short"):
                    return "abc1234\n"
                if args[:2] == ("rev-parse", "--show-toplevel"):
                    return f"{top}\n"
                if args[0] == "status":
                    return status
                if args[0] == "show" and args[1] == "HEAD:README.md":
                    return README_TEXT
                raise source_state.GitError(f"unexpected git {args}")
            return git

        generated = [top / "reports" / "VALIDATION.md", top / "reports" / "figures"]
        clean = ("?? reports/VALIDATION.md\0 M reports/figures/a.png\0?? build/x.o\0?? build-asan/y\0"
                 " M README.md\0")
        with mock.patch.object(source_state, "git", fake(clean)):
            prov = source_state.git_state(top, generated, readme)
        self.assertEqual((prov.commit, prov.changed, prov.clean), ("abc1234", [], True))
        self.assertEqual(prov.commit_line(), "`abc1234`; working tree clean (the report's own files and "
                                             "build directories not counted)")
        self.assertEqual(prov.short(), "commit `abc1234`")

        dirty = clean + "R  solver/new name.cpp\0solver/old.cpp\0 M reports/make_report.py\0"
        with mock.patch.object(source_state, "git", fake(dirty)):
            prov = source_state.git_state(top, generated, readme)
        self.assertEqual(prov.changed, ["reports/make_report.py", "solver/new name.cpp"])
        self.assertFalse(prov.clean)
        self.assertEqual(prov.commit_line(), "`abc1234`; working tree **not clean**: 2 uncommitted paths "
                                             "(`reports/make_report.py`, `solver/new name.cpp`)")
        self.assertEqual(prov.short(), "commit `abc1234` with uncommitted changes")

        def no_repo(source_dir, *args):
            raise source_state.GitError("git rev-parse: fatal: not a git repository")
        with mock.patch.object(source_state, "git", no_repo):
            prov = source_state.git_state(top, generated, readme)
        self.assertIsNone(prov.clean)
        self.assertEqual(prov.commit_line(), "unknown: git rev-parse: fatal: not a git repository; "
                                             "whether the working tree was clean is unknown")

    def test_helpers(self):
        self.assertEqual(make_report.fmt_value(1234567.8), "1.235e+06")
        self.assertEqual(make_report.fmt_value(10000.0), "10000")
        self.assertEqual(make_report.fmt_value(True), "true")
        self.assertEqual(make_report.fmt_value(list(range(20))), "[20 values, 0 .. 19]")
        self.assertEqual(make_report.flatten({"a": {"b": 1, "c": {"d": 2}}, "e": 3}),
                         [("a.b", 1), ("a.c.d", 2), ("e", 3)])
        ev = make_report.evaluate_check({"value": 0.2, "threshold": 0.03, "comparison": "<=",
                                         "expected": "fail", "passed": False, "gating": False})
        self.assertTrue(ev["matches"])
        self.assertFalse(ev["gating"])
        self.assertEqual(ev["outcome"], "expected failure (seed)")
        ev = make_report.evaluate_check({"value": 0.01, "threshold": 0.03, "comparison": "<=",
                                         "expected": "fail", "passed": True, "gating": True})
        self.assertFalse(ev["matches"])
        self.assertEqual(ev["outcome"], "unexpected pass")
        self.assertEqual(make_report.chapters_text([{"seed_section": "3.4, 3.5"}, {"seed_section": "4.2"}]),
                         "seed chapters 3-4")
        self.assertEqual(make_report.section_key({"case": "p", "seed_section": "3.4, 3.5"}), ((3, 4), "p"))
        case = {"case": "c", "checks": [check("reported", 2.0, 1.0, gating=False), check("a", 1.0, 2.0),
                                        check("gated", 3.0, 1.0), check("no value", None, 1.0, passed=False)]}
        self.assertEqual(make_report.first_miss(case, make_report.summarise(case)),
                         "first miss (gating): `gated` is 3, criterion <= 1, expected pass (2 more misses)")


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
                      error: str | None = None) -> dict:
    """A row of bench_network_scaling's JSON (fishbone network: 24 ribs^2 + 1 wetted nodes)."""
    name = f"BM_NetworkScaling/ribs:{ribs}/krylov:{krylov}/iterations:1/manual_time"
    b = {"name": name, "run_name": name, "run_type": "iteration", "family_index": 1,
         "per_family_instance_index": ribs + 100 * krylov, "repetitions": 1, "repetition_index": 0,
         "threads": 1, "iterations": 1, "real_time": 1.3 * step_cpu_s, "cpu_time": 0.01, "time_unit": "s",
         "label": "krylov" if krylov else "dense"}
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
