#!/usr/bin/python3
"""Tests of the validation report (make_report.py, source_state.py); the benchmark report's
are in test_make_benchmarks.py. Run: cd reports && /usr/bin/python3 -m unittest test_make_report
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

    def test_case_tables_shown_before_the_checks(self):
        write_case(self.results, "delta", {
            "case": "delta", "title": "Interaction modes", "seed_section": "5.2", "tier": "full",
            "status": "fail", "checks": [check("modes matched", 1, 2, ">=")], "metrics": {},
            "tables": [{"title": "Modes side by side", "header": ["test", "experiment", "ours"],
                        "rows": [["CT1", "arrest", "**crossing** (missed)"], ["CT2", "a|b", 3.14159]]},
                       {"title": "broken", "rows": "not a list"}]})
        md = self.report()
        self.assertIn("### Modes side by side", md)
        self.assertIn("| test | experiment | ours |", md)
        self.assertIn("| CT1 | arrest | **crossing** (missed) |", md)
        self.assertIn("| CT2 | a\\|b | 3.142 |", md)
        self.assertIn("A table in result.json is malformed", md)
        self.assertLess(md.index("### Modes side by side"), md.index("### Checks"))

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


if __name__ == "__main__":
    unittest.main()
