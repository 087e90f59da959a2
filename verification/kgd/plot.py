"""Figures of the KGD viscosity-storage case (seed Figures 3.4-3.6).

Usage: /usr/bin/python3 plot.py RESULT_DIR
(reads result.json, series_<variant>.csv and analytical.csv written there by verify_kgd)

Each figure has three panels against time: A half-length, B inlet net pressure,
C inlet width, with the M-vertex solution (analytical.csv, computed by the driver from
solver/analytical/kgd.hpp, so the plot and the checks share one formula).
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# (figure file, title, [(variant, marker)]) in the seed's order of Figures 3.4-3.6.
FIGURES = {
    "full": [
        ("kgd_dx_sigma0.png", "KGD, mesh size dx, dt = 0.5 s, sigma0 = 0 (seed Fig. 3.4)",
         [("dx4_s0", "s"), ("dx2_s0", "^"), ("dx1_s0", "D"), ("dx05_s0", "o")]),
        ("kgd_dx_sigma5.png", "KGD, mesh size dx, dt = 0.5 s, sigma0 = 5 MPa (seed Fig. 3.5)",
         [("dx4_s5", "s"), ("dx2_s5", "^"), ("dx1_s5", "D"), ("dx05_s5", "o")]),
        ("kgd_dt.png", "KGD, time step dt, dx = 0.5 m, sigma0 = 0 (seed Fig. 3.6)",
         [("dt2_s0", "s"), ("dt1_s0", "^"), ("dx05_s0", "o"), ("dt025_s0", "D")]),
    ],
    "quick": [
        ("kgd_quick.png", "KGD quick tier: dx = 2 m, dt = 0.5 s, sigma0 = 0",
         [("dx2_s0", "^")]),
    ],
}

PANELS = [  # (column, exact column, scale, y label)
    ("half_length_m", "half_length_m", 1.0, "A: half-length l [m]"),
    ("inlet_net_pressure_Pa", "inlet_net_pressure_Pa", 1e-6, "B: inlet net pressure p0 [MPa]"),
    ("inlet_width_m", "inlet_width_m", 1e3, "C: inlet width w0 [mm]"),
]


def load_csv(path):
    if not os.path.exists(path):
        return None
    data = np.genfromtxt(path, delimiter=",", names=True)
    return np.atleast_1d(data) if data.size else None


def variant_label(metrics, name):
    m = metrics.get(name, {})
    label = m.get("label", name)
    err = m.get("error_at_end")
    if isinstance(err, dict):
        label += " (10 s: l {:+.1f} %, p0 {:+.1f} %, w0 {:+.1f} %)".format(
            100 * err["half_length"], 100 * err["inlet_net_pressure"], 100 * err["inlet_width"])
    elif m and not m.get("completed", False):
        label += " (did not complete)"
    return label


def figure(result_dir, metrics, analytical, filename, title, variants):
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    plotted = 0
    for ax, (column, exact_column, scale, ylabel) in zip(axes, PANELS):
        peaks = []
        if analytical is not None:
            ax.plot(analytical["time_s"], scale * analytical[exact_column], "k-", lw=2,
                    label="M-vertex (zero toughness, no leak-off)")
        for name, marker in variants:
            series = load_csv(os.path.join(result_dir, f"series_{name}.csv"))
            if series is None:
                continue
            # the half-length moves in steps of one joint: draw it as a staircase
            drawstyle = "steps-post" if column == "half_length_m" else "default"
            ax.plot(series["time_s"], scale * series[column], marker + "-", ms=4, lw=1,
                    drawstyle=drawstyle, label=variant_label(metrics, name))
            plotted += 1
            if column == "inlet_net_pressure_Pa":
                finite = series[column][np.isfinite(series[column])]
                if finite.size:
                    peaks.append(float(np.max(finite)))
        if column == "inlet_net_pressure_Pa":
            # p0 ~ t^(-1/3) is unbounded at t = 0: show the range of the data and of the
            # solution from the first quarter second on.
            top = [scale * v for v in peaks] if peaks else []
            if analytical is not None:
                late = analytical["time_s"] >= 0.25
                top.append(scale * float(np.max(analytical[exact_column][late])))
            if top:
                ax.set_ylim(0.0, 1.15 * max(top))
        ax.set_xlabel("time t [s]")
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
    if axes[2].get_legend_handles_labels()[0]:
        axes[2].legend(fontsize=6.5, loc="lower right")  # the emptiest corner of the three panels
    if plotted == 0:
        for ax in axes:
            ax.text(0.5, 0.5, "no completed run data", transform=ax.transAxes, ha="center", color="r")
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(os.path.join(result_dir, filename), dpi=130)
    plt.close(fig)


def main(result_dir):
    with open(os.path.join(result_dir, "result.json")) as f:
        result = json.load(f)
    metrics = result.get("metrics", {})
    analytical = load_csv(os.path.join(result_dir, "analytical.csv"))
    for filename, title, variants in FIGURES.get(result.get("tier", "full"), FIGURES["full"]):
        figure(result_dir, metrics, analytical, filename, title, variants)


if __name__ == "__main__":
    main(sys.argv[1])
