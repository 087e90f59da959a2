"""Likelihood maps of an ensemble: `hfdda_ensemble_plot.py DIR [--times T1,T2,...] [--out FIGDIR]`.

Run with Debian's /usr/bin/python3 (matplotlib Agg, numpy). Reads the files that
write_likelihood_maps (solver/ensemble/likelihood_maps.hpp) leaves in DIR:
likelihood_joints.csv, likelihood_grid.csv and likelihood_convergence.csv, and draws,
like Figures 5.20-5.44 of W. E. Morgan, PhD dissertation, Georgia Institute of
Technology, 2014, for each map time (or the map time nearest each of --times, in
seconds):
  FIGDIR/likelihood_joints_<min>min.png  the likelihood that each joint opened, as line
      darkness from light grey (rarely) to black (always); natural fractures thin;
  FIGDIR/likelihood_grid_<min>min.png  filled contours of the fraction of realisations
      in which a grid cell holds an open joint, and one that holds fluid, in the bands
      < 1 %, 1-25 %, 25-50 % and > 50 %;
and once FIGDIR/likelihood_convergence.png: the largest change of the grid maps between
the first N/2 and all N realisations, against N. FIGDIR defaults to DIR/figures. Prints
each file written. Exit 2 when a file is missing or malformed or the arguments are wrong.
"""
import argparse
import csv
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.collections import LineCollection
    from matplotlib.lines import Line2D
    from matplotlib.ticker import FormatStrFormatter, LogLocator, NullFormatter
    from matplotlib.patches import Patch
except ImportError as e:  # pragma: no cover - depends on the machine
    print(f"hfdda_ensemble_plot: {e}; install Debian's python3-matplotlib and python3-numpy", file=sys.stderr)
    sys.exit(2)

BANDS = [0.0, 0.01, 0.25, 0.5, 1.0]
BAND_NAMES = ["< 1 %", "1-25 %", "25-50 %", "> 50 %"]
BAND_COLOURS = {
    "p_open": ["#ffffff", "#cccccc", "#808080", "#262626"],
    "p_wet": ["#ffffff", "#c6dbef", "#4292c6", "#08306b"],
}
PANEL_TITLES = {"p_open": "open joint in the cell", "p_wet": "fluid in the cell"}


def fail(message):
    print(f"hfdda_ensemble_plot: {message}", file=sys.stderr)
    sys.exit(2)


def read_table(path, columns):
    """The CSV at `path` as a dict of numpy arrays, one per column named."""
    if not os.path.isfile(path):
        fail(f"{path} not found (write it with write_likelihood_maps)")
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        missing = [c for c in columns if c not in (reader.fieldnames or [])]
        if missing:
            fail(f"{path}: missing column(s) {', '.join(missing)}")
        rows = list(reader)
    try:
        return {c: np.array([float(r[c]) for r in rows]) for c in columns}
    except (TypeError, ValueError) as e:
        fail(f"{path}: not a number ({e})")


def minutes_text(time_s):
    return f"{time_s / 60.0:g}"


def grid_geometry(grid):
    """Cell size and the lower-left corner of the grid, from cell centres and indices."""
    ix, iy = grid["ix"], grid["iy"]
    cell = None
    for idx, centre in ((ix, grid["x_centre"]), (iy, grid["y_centre"])):
        if cell is None and idx.size and idx.max() > idx.min():
            lo, hi = np.argmin(idx), np.argmax(idx)
            cell = (centre[hi] - centre[lo]) / (idx[hi] - idx[lo])
    if cell is None:
        cell = 1.0  # a single cell: its size cannot be read back, any scale will do
    xmin = float(np.min(grid["x_centre"] - (ix + 0.5) * cell))
    ymin = float(np.min(grid["y_centre"] - (iy + 0.5) * cell))
    return cell, xmin, ymin, int(ix.max()) + 1, int(iy.max()) + 1


def segments(joints, mask):
    return [[(x1, y1), (x2, y2)] for x1, y1, x2, y2 in
            zip(joints["x1"][mask], joints["y1"][mask], joints["x2"][mask], joints["y2"][mask])]


def aspect(extent):
    return (extent[3] - extent[2]) / (extent[1] - extent[0])


def frame(ax, extent, title):
    xmin, xmax, ymin, ymax = extent
    ax.plot([xmin, xmax, xmax, xmin, xmin], [ymin, ymin, ymax, ymax, ymin], color="0.6", linewidth=0.6)
    ax.set_xlim(xmin, xmax)
    ax.set_ylim(ymin, ymax)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(title, fontsize=9)


def draw_joints(joints, time_s, realisations, extent, path):
    at = joints["time_s"] == time_s
    natural_ever = joints["natural"] == 1  # natural joints seen at any time: the network
    fig, ax = plt.subplots(figsize=(7.5, 6.0 * aspect(extent) + 0.8))
    ax.add_collection(LineCollection(segments(joints, natural_ever), colors="0.85", linewidths=0.4))
    grey = plt.get_cmap("Greys")
    norm = matplotlib.colors.Normalize(0.0, 1.0)
    for natural, width in ((True, 0.9), (False, 2.2)):  # hydraulic fractures over natural ones
        mask = at & (natural_ever == natural)
        order = np.argsort(joints["p_open"][mask], kind="stable")  # darkest drawn last
        p = joints["p_open"][mask][order]
        all_segs = segments(joints, mask)
        segs = [all_segs[i] for i in order]
        ax.add_collection(LineCollection(segs, colors=grey(0.25 + 0.75 * p), linewidths=width))
    shades = matplotlib.colors.ListedColormap(grey(np.linspace(0.25, 1.0, 256)))
    bar = fig.colorbar(matplotlib.cm.ScalarMappable(norm, shades), ax=ax, shrink=0.8)
    bar.set_label("likelihood of propagation (joint open)")
    ax.legend([Line2D([], [], color="0.3", linewidth=2.2), Line2D([], [], color="0.3", linewidth=0.9),
               Line2D([], [], color="0.85", linewidth=0.4)],
              ["hydraulic fracture paths", "natural fractures", "natural fractures (never open here)"],
              loc="upper right", fontsize=7, framealpha=0.9)
    frame(ax, extent, f"Likelihood of propagation at t = {minutes_text(time_s)} min "
                      f"({realisations} realisations)")
    fig.savefig(path, dpi=150, bbox_inches="tight")
    plt.close(fig)
    print(path)


def draw_grid(grid, geometry, joints, time_s, realisations, extent, path):
    cell, xmin, ymin, nx, ny = geometry
    at = grid["time_s"] == time_s
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.2 * aspect(extent) + 1.2), layout="constrained")
    # Values at the cell centres, padded with the edge values out to the grid's border so
    # that the contours fill the whole grid.
    xs = np.concatenate(([xmin], xmin + (np.arange(nx) + 0.5) * cell, [xmin + nx * cell]))
    ys = np.concatenate(([ymin], ymin + (np.arange(ny) + 0.5) * cell, [ymin + ny * cell]))
    for ax, key in zip(axes, ("p_open", "p_wet")):
        values = np.zeros((ny, nx))
        values[grid["iy"][at].astype(int), grid["ix"][at].astype(int)] = grid[key][at]
        padded = np.pad(values, 1, mode="edge")
        ax.contourf(xs, ys, padded, levels=BANDS, colors=BAND_COLOURS[key])
        if joints is not None:
            ax.add_collection(LineCollection(segments(joints, joints["natural"] == 1), colors="0.5", linewidths=0.3))
        frame(ax, extent, f"Likelihood of {PANEL_TITLES[key]}")
        ax.legend([Patch(facecolor=c, edgecolor="0.4", linewidth=0.5) for c in BAND_COLOURS[key]], BAND_NAMES,
                  loc="upper right", fontsize=7, framealpha=0.9, title="of realisations", title_fontsize=7)
    fig.suptitle(f"Likelihood maps at t = {minutes_text(time_s)} min ({realisations} realisations, "
                 f"cells of {cell:g} m)", fontsize=10)
    fig.savefig(path, dpi=150, bbox_inches="tight")
    plt.close(fig)
    print(path)


def draw_convergence(conv, times, path):
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    positive = []
    for i, t in enumerate(times):
        at = conv["time_s"] == t
        if not at.any():
            continue
        for key, style, name in (("max_change_open", "-", "open"), ("max_change_wet", "--", "wet")):
            ax.plot(conv["n"][at], conv[key][at], style, color=colours[i % len(colours)], linewidth=1.0,
                    marker="o" if at.sum() < 30 else None, markersize=2.5,
                    label=f"{name}, t = {minutes_text(t)} min")
            positive.extend(conv[key][at][conv[key][at] > 0])
    if positive and conv["n"].size and conv["n"].min() > 0:
        ax.set_xscale("log")
        ax.set_yscale("log")
        n = np.array([conv["n"].min(), conv["n"].max()])
        ref = max(positive) * np.sqrt(n[0] / n)  # the Monte Carlo rate, for comparison
        ax.plot(n, ref, ":", color="0.5", linewidth=0.8, label="proportional to N^-1/2")
        for axis in (ax.xaxis, ax.yaxis):  # plain numbers at 1, 2, 5 x 10^k: short ranges
            axis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
            axis.set_major_formatter(FormatStrFormatter("%g"))
            axis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("number of realisations N")
    ax.set_ylabel("max over cells of |p(first N/2) - p(all N)|")
    ax.set_title("Convergence of the grid likelihood maps", fontsize=9)
    if ax.lines:
        ax.legend(fontsize=7, ncol=2)
    else:
        ax.text(0.5, 0.5, "no convergence data: fewer than 2 realisations at these times",
                ha="center", va="center", transform=ax.transAxes, fontsize=9)
    ax.grid(True, which="both", linewidth=0.3, color="0.85")
    fig.savefig(path, dpi=150, bbox_inches="tight")
    plt.close(fig)
    print(path)


def main():
    parser = argparse.ArgumentParser(description="draw the likelihood maps of an ensemble in DIR")
    parser.add_argument("dir")
    parser.add_argument("--times", default="", help="comma-separated times [s]; the nearest map times are drawn")
    parser.add_argument("--out", default="", help="folder for the figures (default DIR/figures)")
    args = parser.parse_args()
    fractions = ["realisations", "p_open", "p_open_low", "p_open_high", "p_wet", "p_wet_low", "p_wet_high"]
    joints = read_table(os.path.join(args.dir, "likelihood_joints.csv"),
                        ["time_s", "joint", "x1", "y1", "x2", "y2", "natural"] + fractions)
    grid = read_table(os.path.join(args.dir, "likelihood_grid.csv"),
                      ["time_s", "cell", "ix", "iy", "x_centre", "y_centre"] + fractions)
    conv = read_table(os.path.join(args.dir, "likelihood_convergence.csv"),
                      ["time_s", "n", "max_change_open", "max_change_wet"])
    if grid["time_s"].size == 0:
        fail(f"{os.path.join(args.dir, 'likelihood_grid.csv')} has no rows")
    map_times = np.unique(grid["time_s"])
    try:
        wanted = [float(t) for t in args.times.split(",") if t.strip()]
    except ValueError:
        fail(f"--times '{args.times}': give times in seconds separated by commas")
    times = sorted({map_times[np.argmin(np.abs(map_times - t))] for t in wanted}) if wanted else list(map_times)

    out = args.out or os.path.join(args.dir, "figures")
    os.makedirs(out, exist_ok=True)
    geometry = grid_geometry(grid)
    cell, xmin, ymin, nx, ny = geometry
    extent = (xmin, xmin + nx * cell, ymin, ymin + ny * cell)
    has_joints = joints["time_s"].size > 0
    if not has_joints:
        print("hfdda_ensemble_plot: no joint rows (grid maps only); no joint figures", file=sys.stderr)
    for t in times:
        realisations = int(grid["realisations"][grid["time_s"] == t][0])
        if has_joints:
            draw_joints(joints, t, realisations, extent,
                        os.path.join(out, f"likelihood_joints_{minutes_text(t)}min.png"))
        draw_grid(grid, geometry, joints if has_joints else None, t, realisations, extent,
                  os.path.join(out, f"likelihood_grid_{minutes_text(t)}min.png"))
    draw_convergence(conv, times, os.path.join(out, "likelihood_convergence.png"))


if __name__ == "__main__":
    main()
