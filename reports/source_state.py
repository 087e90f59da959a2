"""Where a validation report's results come from: the git commit and whether the working
tree was clean, the BLAS kernels the results ran on, and the README's generated section
(the text between its summary markers), which a report run may rewrite without making the
tree count as changed. Used by make_report.py; standard library only."""

from __future__ import annotations

import subprocess
from pathlib import Path

README_BEGIN = "<!-- verified-summary:begin -->"
README_END = "<!-- verified-summary:end -->"


class GitError(Exception):
    """git is missing, or a git command failed (the message says which)."""


def git(source_dir: Path, *args: str) -> str:
    """stdout of `git -C source_dir ARGS`; raises GitError."""
    try:
        p = subprocess.run(["git", "-C", str(source_dir), *args], capture_output=True, text=True, timeout=60)
    except FileNotFoundError:
        raise GitError("git is not installed") from None
    except (OSError, subprocess.TimeoutExpired) as e:
        raise GitError(f"git could not be run ({e})") from None
    if p.returncode != 0:
        first = (p.stderr.strip().splitlines() or [f"exit status {p.returncode}"])[0]
        raise GitError(f"git {args[0]}: {first}")
    return p.stdout


def is_build_dir(path: str) -> bool:
    top = path.split("/", 1)[0]
    return top == "build" or top.startswith("build-")


def split_readme(text: str, name: str = "README.md"):
    """(before, generated, after) around the summary markers; raises ValueError naming the
    line and the rule broken when they are missing, repeated or out of order."""
    lines = text.splitlines(keepends=True)
    begins = [i for i, l in enumerate(lines) if l.strip() == README_BEGIN]
    ends = [i for i, l in enumerate(lines) if l.strip() == README_END]
    if len(begins) != 1 or len(ends) != 1:
        where = begins[1:] + ends[1:]
        at = f":{where[0] + 1}" if where else ""
        raise ValueError(f"{name}{at}: marker lines '{README_BEGIN}' and '{README_END}' must each appear "
                         f"exactly once, on lines of their own (found {len(begins)} and {len(ends)})")
    b, e = begins[0], ends[0]
    if e < b:
        raise ValueError(f"{name}:{e + 1}: '{README_END}' comes before '{README_BEGIN}' (line {b + 1})")
    return "".join(lines[:b + 1]), "".join(lines[b + 1:e]), "".join(lines[e:])


def outside_generated(text: str) -> str:
    """The README without its generated section (the whole text if the markers are not usable)."""
    try:
        before, _, after = split_readme(text)
    except ValueError:
        return text
    return before + after


class Provenance:
    """Commit and working-tree state of the source the report was made from."""

    def __init__(self, commit=None, changed=None, problem: str = ""):
        self.commit = commit            # short hash, or None when git could not tell
        self.changed = changed or []    # uncommitted paths that count
        self.problem = problem          # why commit/state are unknown

    @property
    def clean(self):
        return None if self.commit is None else not self.changed

    def commit_line(self) -> str:
        if self.commit is None:
            return f"unknown: {self.problem}; whether the working tree was clean is unknown"
        if not self.changed:
            return (f"`{self.commit}`; working tree clean (the report's own files and build "
                    "directories not counted)")
        shown = ", ".join(f"`{c}`" for c in self.changed[:5]) + (", ..." if len(self.changed) > 5 else "")
        n = len(self.changed)
        return f"`{self.commit}`; working tree **not clean**: {n} uncommitted path{'' if n == 1 else 's'} ({shown})"

    def short(self) -> str:
        """For the README: 'commit `abc1234`', with what is known about the tree."""
        if self.commit is None:
            return "an unknown commit (git could not tell; see the report's header)"
        return f"commit `{self.commit}`" + (" with uncommitted changes" if self.changed else "")


def git_state(source_dir: Path, generated: list[Path], readme: Path | None = None) -> Provenance:
    """Commit and uncommitted paths; the generated report files, build directories and a
    README that differs from HEAD only inside its generated section do not count."""
    try:
        commit = git(source_dir, "rev-parse", "--short", "HEAD").strip()
        top = Path(git(source_dir, "rev-parse", "--show-toplevel").strip()).resolve()
        status = git(source_dir, "status", "--porcelain", "-z", "--untracked-files=all")
    except GitError as e:
        return Provenance(problem=str(e))

    def rel(path: Path):
        try:
            return path.resolve().relative_to(top).as_posix()
        except ValueError:
            return None

    ignore = [r for r in (rel(g) for g in generated) if r]
    readme_rel = rel(readme) if readme is not None else None
    changed = []
    entries = status.split("\0")
    i = 0
    while i < len(entries):
        entry = entries[i]
        i += 1
        if len(entry) < 4:
            continue
        code, path = entry[:2], entry[3:]
        if "R" in code or "C" in code:
            i += 1   # -z puts a rename's original path in the next entry
        if is_build_dir(path) or any(path == ig or path.startswith(ig.rstrip("/") + "/") for ig in ignore):
            continue
        if path == readme_rel and readme_generated_only(source_dir, readme, path):
            continue
        changed.append(path)
    return Provenance(commit=commit, changed=sorted(changed))


def readme_generated_only(source_dir: Path, readme: Path, rel_path: str) -> bool:
    """True when the README differs from HEAD only between the summary markers."""
    try:
        head = git(source_dir, "show", f"HEAD:{rel_path}")
        now = readme.read_text(encoding="utf-8")
    except (GitError, OSError, UnicodeDecodeError):
        return False
    return outside_generated(head) == outside_generated(now)


def update_readme(readme: Path, section: str) -> bool:
    """Replaces the text between the markers; True when the file changed. Raises ValueError."""
    text = readme.read_text(encoding="utf-8")
    before, old, after = split_readme(text, readme.name)
    if old == section:
        return False
    tmp = readme.with_name(readme.name + ".tmp")
    tmp.write_text(before + section + after, encoding="utf-8")
    tmp.replace(readme)
    return True


def kernels_line(cases: list[dict]) -> str:
    """The BLAS kernels the results ran on (result.json "environment"): long runs differ
    in the last bits between OpenBLAS's kernels (docs/design_notes.md section 32), so a
    report made from results of several kernels says which ran where."""
    by_kernel: dict[str, list[str]] = {}
    for case in cases:
        env = case.get("environment")
        kernels = env.get("blas_kernels") if isinstance(env, dict) else None
        by_kernel.setdefault(str(kernels) if kernels else "not recorded", []).append(str(case["dir"]))
    source = "OpenBLAS, `OPENBLAS_CORETYPE` (`scripts/blas_kernels.sh`; docs/design_notes.md section 32)"
    if len(by_kernel) == 1:
        return f"- BLAS kernels: {next(iter(by_kernel))} for every result; {source}"
    parts = [f"{k} ({', '.join(f'`{d}`' for d in dirs)})" for k, dirs in sorted(by_kernel.items())]
    return f"- BLAS kernels: **mixed**: {'; '.join(parts)}; {source}"
