"""Figures of the Monte Carlo ensembles (seed 5.5, 5.6, Figures 5.20-5.44).

Usage: /usr/bin/python3 plot.py RESULT_DIR
(reads result.json and each study's maps in RESULT_DIR/runs/<variant>/, written by
`hfdda ensemble` under verify_ensembles)

ensembles_grid.png: per study, the grid likelihood of propagation at the last map time in
the seed's bands (< 1 %, 1-25 %, 25-50 %, > 50 %). ensembles_joints.png: per study, the
likelihood of each joint opening as line darkness. ensembles_convergence.png (ensemble
tier): the largest change of the grid map between the first N/2 and all N realisations.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, os.pardir, "harness"))
sys.path.insert(0, os.path.join(HERE, os.pardir, os.pardir, "solver", "cli"))
import plot_common  # noqa: E402  (first: selects the Agg backend)
import hfdda_ensemble_plot as maps  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

STUDIES = ["s55_s0", "s55_s12", "s55_fluid_held", "s55_fluid_all", "s56_base", "s56_mu1000", "s56_q2", "s56_fluid"]
TITLES = {"s55_s0": "5.5, dsigma = 0", "s55_s12": "5.5, dsigma = 12 MPa", "s55_fluid_held": "5.5, fluid varied",
          "s55_fluid_all": "5.5, all varied", "s56_base": "5.6 Marcellus", "s56_mu1000": "5.6, 1000 mPa s",
          "s56_q2": "5.6, 2 kg/s", "s56_fluid": "5.6, fluid varied"}
GRID_COLUMNS = ["time_s", "ix", "iy", "x_centre", "y_centre", "realisations", "p_open", "p_wet"]
JOINT_COLUMNS = ["time_s", "x1", "y1", "x2", "y2", "p_open"]


def studies(result_dir, tier):
    suffix = "_few" if tier == "full" else ""
    found = []
    for s in STUDIES:
        d = os.path.join(result_dir, "runs", s + suffix)
        if os.path.isfile(os.path.join(d, "likelihood_grid.csv")):
            found.append((s, d))
    return found


def panel_grid(ax, d, key="p_open"):
    grid = maps.read_table(os.path.join(d, "likelihood_grid.csv"), GRID_COLUMNS)
    cell, xmin, ymin, nx, ny = maps.grid_geometry(grid)
    last = grid["time_s"].max()
    at = grid["time_s"] == last
    values = np.zeros((ny, nx))
    values[grid["iy"][at].astype(int), grid["ix"][at].astype(int)] = grid[key][at]
    xs = np.concatenate(([xmin], xmin + (np.arange(nx) + 0.5) * cell, [xmin + nx * cell]))
    ys = np.concatenate(([ymin], ymin + (np.arange(ny) + 0.5) * cell, [ymin + ny * cell]))
    ax.contourf(xs, ys, np.pad(values, 1, mode="edge"), levels=maps.BANDS, colors=maps.BAND_COLOURS[key])
    ax.set_xlim(xmin, xmin + nx * cell)
    ax.set_ylim(ymin, ymin + ny * cell)
    ax.set_aspect("equal")
    return last, int(grid["realisations"][at][0])


def panel_joints(ax, d):
    joints = maps.read_table(os.path.join(d, "likelihood_joints.csv"), JOINT_COLUMNS)
    if joints["time_s"].size == 0:
        return
    at = joints["time_s"] == joints["time_s"].max()
    order = np.argsort(joints["p_open"][at], kind="stable")
    segs = maps.segments(joints, at)
    p = joints["p_open"][at][order]
    ax.add_collection(LineCollection([segs[i] for i in order], colors=plt.get_cmap("Greys")(0.2 + 0.8 * p),
                                     linewidths=1.2))
    ax.set_xlim(-125, 125)
    ax.set_ylim(-125, 125)
    ax.set_aspect("equal")


def figure(found, name, draw, result_dir, legend=None):
    n = len(found)
    cols = min(4, n)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(3.2 * cols, 3.3 * rows + 0.6), squeeze=False)
    for ax in axes.flat[n:]:
        ax.axis("off")
    for ax, (s, d) in zip(axes.flat, found):
        info = draw(ax, d)
        title = TITLES[s] + (f"\n{info[1]} realisations, t = {info[0] / 60:g} min" if info else "")
        ax.set_title(title, fontsize=8)
        ax.tick_params(labelsize=6)
    if legend:
        fig.legend(*legend, loc="lower center", ncol=4, fontsize=7)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    plot_common.save(fig, result_dir, name)


def convergence(found, result_dir):
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for s, d in found:
        conv = maps.read_table(os.path.join(d, "likelihood_convergence.csv"), ["time_s", "n", "max_change_open"])
        if conv["n"].size == 0:
            continue
        at = conv["time_s"] == conv["time_s"].max()
        ax.plot(conv["n"][at], conv["max_change_open"][at], label=TITLES[s], linewidth=1.0)
    ax.set_xlabel("number of realisations N")
    ax.set_ylabel("max over cells of |p(first N/2) - p(all N)|, open")
    ax.set_xscale("log")
    ax.grid(True, linewidth=0.3)
    if ax.lines:
        ax.legend(fontsize=7)
    fig.tight_layout()
    plot_common.save(fig, result_dir, "ensembles_convergence.png")


def main(result_dir):
    tier, _ = plot_common.read_result(result_dir)
    if tier == "quick":
        return
    found = studies(result_dir, tier)
    if not found:
        return
    bands = ([Patch(facecolor=c, edgecolor="0.4", linewidth=0.5) for c in maps.BAND_COLOURS["p_open"]],
             ["open: " + b for b in maps.BAND_NAMES])
    figure(found, "ensembles_grid.png", panel_grid, result_dir, bands)
    figure(found, "ensembles_joints.png", lambda ax, d: panel_joints(ax, d), result_dir)
    if tier == "ensemble":
        convergence(found, result_dir)


if __name__ == "__main__":
    main(sys.argv[1])
