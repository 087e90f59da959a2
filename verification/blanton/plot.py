"""Figures of Blanton's interaction experiments (seed 5.2, Figure 5.4).

Usage: /usr/bin/python3 plot.py RESULT_DIR
(reads result.json, modes.csv, joints_<variant>.csv and, if present, criteria.csv written
there by verify_blanton)

blanton_quick.png / the panels of blanton_tests.png: the 30 cm block at the end of a run,
drawn like the seed's figures: natural fracture thin black, open joints thick dark grey,
joints that broke and closed again or hold fluid without being open light grey, the
injection point as a circle. blanton_map.png: the mode of every run of the sweep over
approach angle and differential stress (like the seed's Figure 5.4), Blanton's eleven
tests as large hollow markers with their observed mode, and the analytical crossing
boundaries of docs/interaction_criteria.md when criteria.csv is there.
"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "harness"))
import plot_common  # noqa: E402  (first: selects the Agg backend)

import matplotlib.pyplot as plt  # noqa: E402
from pattern_plots import add_pattern  # noqa: E402

HALF = 0.15
MARKERS = {"crossing": ("^", "tab:red"), "opening": ("s", "tab:blue"), "arrest": ("o", "tab:green"),
           "none": ("x", "k")}


def rows(path):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return list(csv.DictReader(f))


def draw_joints(ax, result_dir, variant, title):
    joints = rows(os.path.join(result_dir, f"joints_{variant}.csv"))
    ax.set_xlim(-HALF, HALF)
    ax.set_ylim(-HALF, HALF)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_title(title, fontsize=8)
    if not joints:
        plot_common.mark_no_data([ax])
        return
    add_pattern(ax, joints, lambda r: r["invaded"] == "1" or r["broken"] == "1")
    ax.plot([0], [0], "ko", mfc="none", ms=4)


def main(result_dir):
    tier, metrics = plot_common.read_result(result_dir)
    modes = rows(os.path.join(result_dir, "modes.csv"))
    if tier == "quick":
        fig, axes = plt.subplots(1, 2, figsize=(8, 4))
        for ax, (variant, name) in zip(axes, [("ct20_quick", "CT20"), ("ct22_map_quick", "CT22 (map)")]):
            m = next((r for r in modes if r["variant"] == variant), None)
            title = f"{name}: {m['mode']} (Blanton: {m['blanton_mode']}), t = {m['time_s']} s" if m else name
            draw_joints(ax, result_dir, variant, title)
        plot_common.save(fig, result_dir, "blanton_quick.png")
        return
    tests = [r for r in modes if r["group"] == "test"]
    fig, axes = plt.subplots(3, 4, figsize=(11, 8.5))
    for ax, r in zip(axes.flat, tests):
        mark = "" if r["mode"] == r["blanton_mode"] else "  (MISS)"
        draw_joints(ax, result_dir, r["variant"],
                    f"{r['test_id']}: {r['theta_deg']} deg, {float(r['delta_sigma_MPa']):g} MPa\n"
                    f"ours {r['mode']}, Blanton {r['blanton_mode']}{mark}")
    for ax in list(axes.flat)[len(tests):]:
        ax.axis("off")
    plot_common.save(fig, result_dir, "blanton_tests.png")

    fig, ax = plt.subplots(figsize=(7, 5))
    for mode, (marker, color) in MARKERS.items():
        pts = [(float(r["theta_deg"]), float(r["delta_sigma_MPa"])) for r in modes
               if r["group"] == "map" and r["mode"] == mode]
        if pts:
            ax.scatter(*zip(*pts), marker=marker, color=color, s=30, label=f"HFDDA: {mode}")
        obs = [(float(r["theta_deg"]), float(r["delta_sigma_MPa"])) for r in tests if r["blanton_mode"] == mode]
        if obs:
            ax.scatter(*zip(*obs), marker=marker, facecolors="none", edgecolors=color, s=160, linewidths=1.5,
                       label=f"Blanton: {mode}")
    for curve in {r["criterion"] for r in rows(os.path.join(result_dir, "criteria.csv"))}:
        pts = [(float(r["theta_deg"]), float(r["delta_sigma_MPa"])) for r in rows(os.path.join(result_dir, "criteria.csv"))
               if r["criterion"] == curve and r["delta_sigma_MPa"] not in ("inf", "nan")]
        if len(pts) == 1:
            ax.plot(*pts[0], "k*", ms=12, label=f"{curve}: {pts[0][1]:.1f} MPa")
        elif pts:
            ax.plot(*zip(*sorted(pts)), "--", lw=1.2, label=curve)
    ax.set_xlabel("approach angle theta [deg]")
    ax.set_ylabel("differential stress sigma_max - sigma_min [MPa]")
    ax.set_xlim(25, 95)
    ax.set_ylim(-1, 17)
    ax.legend(fontsize=7, loc="upper left", ncol=2)
    ax.set_title("Interaction map (sigma_min = 5 MPa), seed Figure 5.4")
    plot_common.save(fig, result_dir, "blanton_map.png")


if __name__ == "__main__":
    main(sys.argv[1])
