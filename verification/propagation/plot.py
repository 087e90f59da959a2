"""Figures of the propagation verification (seed 3.4-3.5, Figures 3.13-3.17, 3.19-3.20, 3.22-3.23).

Usage: /usr/bin/python3 plot.py RESULT_DIR
(reads result.json, joints_<variant>.csv, series_<variant>.csv and interface_bimaterial.csv
written there by verify_propagation)

Pattern figures: the 40 m x 40 m inner domain with the mesh joints in light grey and the
fluid-filled joints in black after 30 s (or at the step where a run stopped, said in the
panel title), the injection point as a black circle, as in the seed's figures. Case (e)
draws the weak -45 degree diagonals in a darker grey (seed Fig. 3.18). Case (d) adds the
mass ledger over time (seed Fig. 3.17), case (g) the vertical displacement of the two
faces of the interface (seed Fig. 3.23).
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "harness"))
import plot_common  # noqa: E402  (first: selects the Agg backend)
from plot_common import load_csv  # noqa: E402

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

INNER = 20.0
PATTERNS = {  # figure -> [(variant, panel letter)]
    "full": [
        ("propagation_free.png", "Free propagation (seed Fig. 3.13)", [("free_s0", "A"), ("free_s5", "B")]),
        ("propagation_cross.png", "Cross-shaped start (seed Fig. 3.14)", [("cross_s0", "A"), ("cross_s5", "B")]),
        ("propagation_diagonal.png", "Diagonal-only propagation (seed Fig. 3.15)",
         [("diagonal_s0", "A"), ("diagonal_s5", "B")]),
        ("propagation_leakoff.png", "Leak-off C_L = 0.02 mm/s^0.5 (seed Fig. 3.16)", [("leakoff_s0", "")]),
        ("propagation_weak_diagonal.png", "Weaker -45 deg diagonals (seed Figs. 3.18-3.19)",
         [("weak_diagonal", "")]),
        ("propagation_delaunay.png", "Delaunay mesh (seed Fig. 3.20)", [("delaunay", "")]),
        ("propagation_bimaterial.png", "Bi-material interface, E = 25 GPa above, 5 GPa below (seed Fig. 3.22)",
         [("bimaterial", "")]),
        ("propagation_time_step.png", "Free propagation at dsigma = 5 MPa with three time steps (beyond the seed)",
         [("free_s5_dt05", "dt 0.5 s"), ("free_s5", "dt 1 s"), ("free_s5_dt2", "dt 2 s")]),
    ],
    "quick": [
        ("propagation_quick.png", "Quick tier: free propagation at dsigma = 0 and 5 MPa, weaker -45 deg diagonals",
         [("free_s0", "A"), ("free_s5", "B"), ("weak_diagonal", "C")]),
    ],
}


def panel_title(metrics, name, letter):
    m = metrics.get(name, {})
    title = (letter + ": " if letter else "") + m.get("label", name)
    if not m:
        return title + "\n(not run)"
    if not m.get("completed", False):
        title += "\nrun STOPPED at t = {:g} s".format(m.get("time_reached_s", 0.0))
    else:
        title += "\nafter {:g} s".format(m.get("time_reached_s", 0.0))
    e = m.get("extent_m")
    if isinstance(e, dict):
        title += ": x {:+.1f}..{:+.1f} m, y {:+.1f}..{:+.1f} m".format(-e["left"], e["right"], -e["down"], e["up"])
    return title


def draw_pattern(ax, result_dir, metrics, name, letter, weak_diagonals=False):
    joints = load_csv(os.path.join(result_dir, f"joints_{name}.csv"))
    ax.set_title(panel_title(metrics, name, letter), fontsize=8.5)
    ax.set_xlim(-INNER, INNER)
    ax.set_ylim(-INNER, INNER)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    if joints is None:
        plot_common.mark_no_data([ax], "no joint data")
        return
    p = np.column_stack([joints["px"], joints["py"]])
    q = np.column_stack([joints["qx"], joints["qy"]])
    inside = np.all(np.abs(np.hstack([p, q])) <= INNER + 1e-6, axis=1)
    wet = joints["wetted"] > 0.5
    grey = inside & ~wet
    segments = np.stack([p, q], axis=1)
    if weak_diagonals:
        d = q - p
        minus45 = (d[:, 0] * d[:, 1] < -1e-9) & (joints["breakable"] > 0.5)
        ax.add_collection(LineCollection(segments[grey & ~minus45], colors="0.82", linewidths=0.5))
        ax.add_collection(LineCollection(segments[grey & minus45], colors="0.45", linewidths=0.7,
                                         label="weak -45 deg diagonals (T0 = 0.1 MPa)"))
    else:
        ax.add_collection(LineCollection(segments[grey], colors="0.82", linewidths=0.5))
    ax.add_collection(LineCollection(segments[wet], colors="k", linewidths=2.2, label="fluid-filled joints"))
    ends = np.vstack([p[wet], q[wet]])
    if ends.size:
        ax.plot(ends[:, 0], ends[:, 1], "k.", ms=4)
    ax.plot([0], [0], "o", ms=9, mfc="k", mec="k", label="injection point")
    ax.legend(fontsize=7, loc="lower right", framealpha=0.9)


def pattern_figure(result_dir, metrics, filename, title, panels):
    fig, axes = plt.subplots(1, len(panels), figsize=(6.0 * len(panels), 6.4), squeeze=False)
    for ax, (name, letter) in zip(axes[0], panels):
        draw_pattern(ax, result_dir, metrics, name, letter, weak_diagonals=(name == "weak_diagonal"))
    fig.suptitle(title)
    plot_common.save(fig, result_dir, filename)


def mass_figure(result_dir, metrics):
    s = load_csv(os.path.join(result_dir, "series_leakoff_s0.csv"))
    fig, ax = plt.subplots(figsize=(7, 4.8))
    if s is None:
        plot_common.mark_no_data([ax], "no data")
    else:
        t = s["time_s"]
        total_in = s["mass_initial_kg"] + s["mass_injected_kg"]
        ax.plot(t, s["mass_stored_kg"], "s-", ms=4, label="stored in the fractures")
        ax.plot(t, s["mass_leaked_kg"], "^-", ms=4, label="cumulative leak-off")
        ax.plot(t, s["mass_stored_kg"] + s["mass_leaked_kg"], "o", ms=7, mfc="none", label="stored + leaked")
        ax.plot(t, total_in, "k-", lw=1.5, label="initial + injected")
        worst = float(np.nanmax(np.abs(s["ledger_error"]))) if s.size else float("nan")
        ax.text(0.02, 0.97, "max |in - stored - leaked| / in = {:.1e}".format(worst), transform=ax.transAxes,
                va="top", fontsize=8)
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("fluid mass per metre [kg]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title("Mass conservation with leak-off, dsigma = 0 (seed Fig. 3.17)")
    plot_common.save(fig, result_dir, "propagation_leakoff_mass.png")


def faces_figure(result_dir, metrics):
    f = load_csv(os.path.join(result_dir, "interface_bimaterial.csv"))
    fig, ax = plt.subplots(figsize=(8, 4.4))
    if f is None:
        plot_common.mark_no_data([ax], "no fluid-filled interface joints")
    else:
        order = np.argsort(f["x_m"], kind="stable")
        x = f["x_m"][order]
        ax.plot(x, 1e3 * f["v_upper_m"][order], "o-", ms=4, label="upper face (E = 25 GPa)")
        ax.plot(x, 1e3 * f["v_lower_m"][order], "s-", ms=4, label="lower face (E = 5 GPa)")
        ax.axhline(0.0, color="0.5", lw=0.8)
        i = metrics.get("bimaterial", {}).get("interface", {})
        if i.get("mean_abs_v_upper_m"):
            ax.text(0.02, 0.04, "mean |v|: upper {:.3f} mm, lower {:.3f} mm (ratio {:.2f})".format(
                1e3 * i["mean_abs_v_upper_m"], 1e3 * i["mean_abs_v_lower_m"],
                i["mean_abs_v_lower_m"] / i["mean_abs_v_upper_m"]), transform=ax.transAxes, fontsize=8)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("vertical displacement v [mm]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    ax.set_title("Faces of the fluid-filled interface joints (seed Fig. 3.23; in-situ stress: fluid loading only)",
                 fontsize=9)
    plot_common.save(fig, result_dir, "propagation_bimaterial_faces.png")


def main(result_dir):
    tier, metrics = plot_common.read_result(result_dir)
    for filename, title, panels in plot_common.for_tier(PATTERNS, tier):
        pattern_figure(result_dir, metrics, filename, title, panels)
    if tier == "full":
        mass_figure(result_dir, metrics)
        faces_figure(result_dir, metrics)


if __name__ == "__main__":
    main(sys.argv[1])
