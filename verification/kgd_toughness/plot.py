"""Figures of the KGD toughness-storage case (seed Figures 4.11-4.14).

Usage: /usr/bin/python3 plot.py RESULT_DIR
(reads result.json, series_<variant>.csv and analytical_<variant>.csv written there by
verify_kgd_toughness)

Each figure has three panels against time, as in the seed: A half-length, B inlet
pressure (net: there is no background stress), C inlet width, with the K-vertex solution
of each variant's toughness (analytical_<variant>.csv, computed by the driver from
solver/analytical/kgd.hpp, so the plot and the checks share one formula). Variants with
the same K_IC share one curve.
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# (figure file, title, [(variant, marker)]) in the seed's order of Figures 4.11-4.14.
FIGURES = {
    "full": [
        ("kgd_toughness_t1.png", "KGD toughness storage, T0 = 1 MPa, L = 0.5 and 1 m (seed Fig. 4.11)",
         [("l05_t1", "o"), ("l1_t1", "s")]),
        ("kgd_toughness_t5.png", "KGD toughness storage, T0 = 5 MPa, L = 0.5 and 1 m (seed Fig. 4.12)",
         [("l05_t5", "o"), ("l1_t5", "s")]),
        ("kgd_toughness_k0886.png", "KGD toughness storage, K_IC = 0.886 MPa m^0.5 (seed Fig. 4.13)",
         [("l05_t1", "o"), ("l1_t0707", "s"), ("l1_k0886", "x")]),
        ("kgd_toughness_k443.png", "KGD toughness storage, K_IC = 4.43 MPa m^0.5 (seed Fig. 4.14, erratum 7)",
         [("l05_t5", "o"), ("l1_t3536", "s"), ("l1_k443", "x")]),
    ],
    "quick": [
        ("kgd_toughness_quick.png", "KGD toughness storage, quick tier: L = 1 m, T0 = 1 MPa",
         [("quick", "s")]),
    ],
}

PANELS = [  # (column, scale, y label)
    ("half_length_m", 1.0, "A: half-length l [m]"),
    ("inlet_net_pressure_Pa", 1e-6, "B: inlet pressure p0 [MPa]"),
    ("inlet_width_m", 1e3, "C: inlet width w0 [mm]"),
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
        label += " (end: l {:+.1f} %, p0 {:+.1f} %, w0 {:+.1f} %)".format(
            100 * err["half_length"], 100 * err["inlet_net_pressure"], 100 * err["inlet_width"])
    elif m and not m.get("completed", False):
        label += " (did not complete)"
    return label


def figure(result_dir, metrics, filename, title, variants):
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    plotted = 0
    drawn_k = []  # toughness of the analytical curves drawn, so a shared curve is drawn once
    for name, marker in variants:
        series = load_csv(os.path.join(result_dir, f"series_{name}.csv"))
        exact = load_csv(os.path.join(result_dir, f"analytical_{name}.csv"))
        kic = metrics.get(name, {}).get("fracture_toughness_Pa_sqrt_m")
        new_curve = exact is not None and kic is not None and all(
            abs(kic - k) > 1e-3 * k for k in drawn_k)
        if new_curve:
            drawn_k.append(kic)
        for ax, (column, scale, ylabel) in zip(axes, PANELS):
            if new_curve:
                ax.plot(exact["time_s"], scale * exact[column], "-", color="k", lw=2,
                        alpha=1.0 if len(drawn_k) == 1 else 0.5,
                        label="K-vertex, K_IC = {:.3g} MPa m^0.5".format(kic * 1e-6))
            if series is None:
                continue
            # the half-length moves in steps of one joint: draw it as a staircase
            drawstyle = "steps-post" if column == "half_length_m" else "default"
            ax.plot(series["time_s"], scale * series[column], marker + "-", ms=4, lw=1,
                    drawstyle=drawstyle, label=variant_label(metrics, name))
        if series is not None:
            plotted += 1
    for ax, (column, scale, ylabel) in zip(axes, PANELS):
        if column == "inlet_net_pressure_Pa":
            # p0 ~ t^(-1/3) is unbounded at t = 0: show the range from t = 1 s on
            top = []
            for line in ax.get_lines():
                x, y = line.get_xdata(), line.get_ydata()
                late = np.asarray(x) >= 1.0
                if np.any(late):
                    top.append(float(np.nanmax(np.asarray(y)[late])))
            if top:
                ax.set_ylim(0.0, 1.3 * max(top))
        ax.set_xlabel("time t [s]")
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=6.5, loc="lower right")  # the curves rise from the lower left
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
    for filename, title, variants in FIGURES.get(result.get("tier", "full"), FIGURES["full"]):
        figure(result_dir, metrics, filename, title, variants)


if __name__ == "__main__":
    main(sys.argv[1])
