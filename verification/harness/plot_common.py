"""Pieces every verification case's plot.py repeats: reading the result directory that
verify_<case> wrote (result.json and the case's CSV files), the "no data" marker and
saving a figure (verification/README.md). The KGD-type time panels are in kgd_plots.py.

A case's plot.py imports it with the harness folder on sys.path, found from the
script's own location, so it works from any working directory (reports/make_report.py
runs plot.py from the repository root):

    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "harness"))
    import plot_common  # noqa: E402

Debian's /usr/bin/python3 with matplotlib (Agg) and numpy.
"""
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def load_csv(path):
    """A CSV file with a header row as a numpy record array (one record per row, so a
    single row still indexes as an array); None if the file is missing or has no rows."""
    if not os.path.exists(path):
        return None
    data = np.genfromtxt(path, delimiter=",", names=True)
    return np.atleast_1d(data) if data.size else None


def read_result(result_dir):
    """(tier, metrics) of RESULT_DIR/result.json; the tier defaults to "full"."""
    with open(os.path.join(result_dir, "result.json")) as f:
        result = json.load(f)
    return result.get("tier", "full"), result.get("metrics", {})


def for_tier(figures, tier):
    """The figure list of a tier from a {tier: [...]} table (the full tier's if the tier has none)."""
    return figures.get(tier, figures["full"])


def mark_no_data(axes, text="no completed run data"):
    """Writes `text` in red across each of the axes (a figure without data must say so)."""
    for ax in axes:
        ax.text(0.5, 0.5, text, transform=ax.transAxes, ha="center", color="r")


def save(fig, result_dir, filename, dpi=130):
    """Lays out, writes RESULT_DIR/filename and closes the figure."""
    fig.tight_layout()
    fig.savefig(os.path.join(result_dir, filename), dpi=dpi)
    plt.close(fig)
