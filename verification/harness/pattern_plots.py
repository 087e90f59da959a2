"""Fracture patterns drawn like the seed's figures 5.10-5.19, for the network cases.

Natural fractures thin black, open joints thick dark grey, joints invaded by fluid
without being open lighter thick grey, the injection point as a circle; from the
joints_<variant>.csv files that harness/fracture_pattern.hpp writes (initial mesh).
"""
import csv
import os

import plot_common

import matplotlib.pyplot as plt
from matplotlib.collections import LineCollection


def rows(path):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return list(csv.DictReader(f))


def draw(ax, result_dir, variant, title, summary, half=125.0):
    joints = rows(os.path.join(result_dir, f"joints_{variant}.csv"))
    ax.set_xlim(-half, half)
    ax.set_ylim(-half, half)
    ax.set_aspect("equal")
    ax.tick_params(labelsize=7)
    s = summary.get(variant)
    if s:
        title += (f"\nopen {float(s['open_length_m']):.0f} m ({100 * float(s['open_natural_fraction']):.0f} % natural),"
                  f" band {float(s['open_x_extent_m']):.0f} x {float(s['open_y_extent_m']):.0f} m")
    ax.set_title(title, fontsize=8)
    if not joints:
        plot_common.mark_no_data([ax])
        return
    add_pattern(ax, joints, lambda r: r["invaded"] == "1")
    ax.plot([0], [0], "ko", mfc="none", ms=4)


def add_pattern(ax, joints, closed_but_marked):
    """The seed's drawing of a pattern from joint rows (px, py, qx, qy, natural, open, ...):
    natural thin black, open thick dark grey, and the rows that are not open but for which
    closed_but_marked(row) holds (invaded, or broken and closed again) thick light grey."""
    seg = lambda r: [(float(r["px"]), float(r["py"])), (float(r["qx"]), float(r["qy"]))]
    natural = [seg(r) for r in joints if r["natural"] == "1"]
    opened = [seg(r) for r in joints if r["open"] == "1"]
    closed = [seg(r) for r in joints if r["open"] != "1" and closed_but_marked(r)]
    ax.add_collection(LineCollection(closed, colors="0.7", linewidths=2.5))
    ax.add_collection(LineCollection(natural, colors="k", linewidths=0.6))
    ax.add_collection(LineCollection(opened, colors="0.25", linewidths=2.5))


def panels(result_dir, summary, entries, filename, ncols):
    nrows = (len(entries) + ncols - 1) // ncols
    fig, axes = plt.subplots(nrows, ncols, figsize=(4.2 * ncols, 4.4 * nrows), squeeze=False)
    for ax, (variant, title) in zip(axes.flat, entries):
        draw(ax, result_dir, variant, title, summary)
    for ax in list(axes.flat)[len(entries):]:
        ax.axis("off")
    fig.suptitle("natural fractures: thin black; open joints: thick dark grey;\ninvaded, not open: light grey",
                 fontsize=8)
    plot_common.save(fig, result_dir, filename)
