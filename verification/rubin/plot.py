#!/usr/bin/python3
"""Figures of the Rubin case (seed 3.3, Figures 3.8-3.9) from a result directory:
ours (series_<variant>.csv), Rubin's measurements (experiment.csv) and the peer
simulator (peer.csv, clock shifted by 3.7 s), all in SI units, plotted in mm, um, MPa.

Usage: plot.py RESULT_DIR
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

QUANTITIES = [  # column, axis label, factor from SI
    ("wellbore_pressure_Pa", "wellbore pressure [MPa]", 1e-6),
    ("pressure_15mm_Pa", "pressure at x = 15 mm [MPa]", 1e-6),
    ("pressure_41mm_Pa", "pressure at x = 41 mm [MPa]", 1e-6),
    ("half_length_m", "half-length [mm]", 1e3),
    ("aperture_28p5mm_m", "aperture at x = 28.5 mm [um]", 1e6),
]


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return rows


def column(rows, name, factor):
    t, v = [], []
    for r in rows:
        if r.get(name, "") != "":
            t.append(float(r["time_s"]))
            v.append(float(r[name]) * factor)
    return t, v


def panel(ax, runs, experiment, peer, name, label, factor):
    for variant, rows in runs:
        ax.plot(*column(rows, name, factor), label=f"HFDDA {variant}")
    if peer:
        ax.plot(*column(peer, name, factor), "k--", label="peer (GEOS)")
    if experiment:
        ax.plot(*column(experiment, name, factor), "ko", label="Rubin (1983)")
    ax.axvline(10.0, color="0.7", lw=0.8)
    ax.set_xlabel("time [s]")
    ax.set_ylabel(label)
    ax.grid(alpha=0.3)


def main(out):
    runs = []
    for f in sorted(os.listdir(out)):
        if f.startswith("series_") and f.endswith(".csv"):
            runs.append((f[len("series_"):-4], read(os.path.join(out, f))))
    exp_path, peer_path = os.path.join(out, "experiment.csv"), os.path.join(out, "peer.csv")
    experiment = read(exp_path) if os.path.exists(exp_path) else []
    peer = read(peer_path) if os.path.exists(peer_path) else []
    quick = any(v.startswith("quick") for v, _ in runs)
    if quick:
        fig, axes = plt.subplots(1, 3, figsize=(13, 3.8))
        for ax, q in zip(axes, [QUANTITIES[0], QUANTITIES[3], QUANTITIES[4]]):
            panel(ax, runs, experiment, peer, *q)
            ax.set_xlim(0, 25)
        axes[0].legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "rubin_quick.png"), dpi=110)
        return
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8))
    for ax, q in zip(axes, QUANTITIES[:3]):
        panel(ax, runs, experiment, peer, *q)
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "rubin_pressures.png"), dpi=110)
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.8))
    for ax, q in zip(axes, QUANTITIES[3:]):
        panel(ax, runs, experiment, peer, *q)
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "rubin_geometry.png"), dpi=110)


if __name__ == "__main__":
    main(sys.argv[1])
