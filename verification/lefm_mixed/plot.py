"""Figures of the mixed-mode LEFM case (seed 4.4, Figure 4.10).

Usage: /usr/bin/python3 plot.py RESULT_DIR
(reads result.json, failure_stress.csv, relations.csv and failed_<variant>.csv written
there by verify_lefm_mixed)

lefm_mixed_failure_stress.png: as seed Figure 4.10, one panel per T0: the far-field stress
s [MPa] at which a joint has failed on both sides of the crack against the half-length a
[m], DDA runs against the corrected G-criterion relation (erratum 5), the seed's eq. 4.30
and the exact-field estimate; the curves come from the driver (analytical/lefm_mixed.hpp),
so the plot and the checks share one formula.
lefm_mixed_tips.png (full tier: a = 3 m, T0 = 1 MPa; quick tier: lefm_mixed_tips_quick.png):
the initial crack and the failed joints of the inner domain at the stop level, whole and
near the tips, with the -43.2 deg maximum hoop stress direction at each tip.
lefm_mixed_rosettes.png (full tier, when the study ran the tip-rosette variants r_b*):
the toughness criterion at beta = 15, 45, 60 deg, failure stress against a with the LEFM
relation K_IC / (cos(beta) sqrt(pi a)), and the kink at both tips against the maximum hoop
stress direction over beta.
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def load_csv(path):
    if not os.path.exists(path):
        return None
    data = np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="utf-8")
    return np.atleast_1d(data) if data.size else None


def failure_stress_figure(out, runs, curves):
    strengths = sorted(set(float(t) for t in curves["tensile_strength_Pa"])) if curves is not None else []
    if not strengths:
        return
    fig, axes = plt.subplots(1, len(strengths), figsize=(6.0 * len(strengths), 4.6), squeeze=False)
    for k, (ax, t0) in enumerate(zip(axes[0], strengths)):
        c = curves[curves["tensile_strength_Pa"] == t0]
        a = c["half_length_m"]
        ax.plot(a, c["g_relation_Pa"] / 1e6, "-", color="tab:blue", label="corrected G-criterion (erratum 5)")
        ax.plot(a, c["eq430_Pa"] / 1e6, "--", color="tab:gray", label="seed eq. 4.30 as printed")
        ax.plot(a, c["exact_field_Pa"] / 1e6, ":", color="tab:green", label="exact-field estimate")
        uniform = t0 / math.cos(math.radians(15.0)) ** 2
        ax.plot([0.0], [uniform / 1e6], "v", color="tab:green", ms=7, label="a = 0: T0 / cos^2(15 deg)")
        if runs is not None:
            r = runs[runs["tensile_strength_Pa"] == t0]
            r = r[np.isfinite(r["stop_Pa"])]
            # beta = 30 deg on the seed's grid only (the rosette runs have figures of their own)
            r = r[np.array([not str(v).startswith("r_") for v in r["variant"]], dtype=bool)]
            tough = np.array([str(v).startswith("e_") for v in r["variant"]], dtype=bool)
            ax.plot(r["half_length_m"][~tough], r["stop_Pa"][~tough] / 1e6, "o", color="tab:red", ms=7,
                    label="DDA, strength rule")
            if tough.any():
                ax.plot(r["half_length_m"][tough], r["stop_Pa"][tough] / 1e6, "D", color="tab:purple", ms=6,
                        label="DDA, toughness criterion (K_IC from T0, eq. 4.13)")
        ax.set_xlim(0.0, 5.5)
        ax.set_ylim(0.0, 1.6 * t0 / 1e6)
        ax.set_xlabel("crack half-length a [m]")
        ax.set_ylabel("far-field stress at failure s [MPa]")
        ax.set_title("{}: T0 = {:g} MPa, L = 1 m, beta = 30 deg".format("AB"[k % 2], t0 / 1e6))
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Mode I fracture in mixed-mode loading (seed Fig. 4.10)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "lefm_mixed_failure_stress.png"), dpi=130)
    plt.close(fig)


def draw_joints(ax, joints, half_length):
    for row in joints:
        xs, ys = [row["px_m"], row["qx_m"]], [row["py_m"], row["qy_m"]]
        if row["initially_open"] == 1:
            ax.plot(xs, ys, "-", color="black", lw=3)
        elif row["ends_failed"] == 2:
            ax.plot(xs, ys, "-", color="tab:red", lw=2)
        else:
            ax.plot(xs, ys, "-", color="tab:orange", lw=1.2)
    if half_length > 0:
        theta = math.radians(-43.2213)
        for tip, ahead in ((half_length, 1.0), (-half_length, -1.0)):
            dx, dy = ahead * math.cos(theta), ahead * math.sin(theta)
            ax.plot([tip, tip + 1.5 * dx], [0, 1.5 * dy], "--", color="tab:blue", lw=1)
    ax.set_aspect("equal")
    ax.grid(alpha=0.3)


def tips_figure(out, metrics, variant, name):
    joints = load_csv(os.path.join(out, "failed_{}.csv".format(variant)))
    if joints is None:
        return
    m = metrics.get(variant, {})
    a = float(m.get("half_length_m", 0.0))
    stop = (m.get("failure_stress_Pa") or {}).get("dda")
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8), gridspec_kw={"width_ratios": [1.6, 1, 1]})
    draw_joints(axes[0], joints, a)
    axes[0].set_xlim(-15, 15)
    axes[0].set_ylim(-10, 10)
    axes[0].set_title("inner domain at the stop level")
    for ax, tip, title in ((axes[1], -a, "left tip"), (axes[2], a, "right tip")):
        draw_joints(ax, joints, a)
        ax.set_xlim(tip - 2.5, tip + 2.5)
        ax.set_ylim(-2.5, 2.5)
        ax.set_title(title)
    axes[0].plot([], [], "-", color="black", lw=3, label="initial crack")
    axes[0].plot([], [], "-", color="tab:red", lw=2, label="failed joint (both ends)")
    axes[0].plot([], [], "-", color="tab:orange", lw=1.2, label="one end failed")
    axes[0].legend(fontsize=8, loc="upper right")
    fig.suptitle("{}: failed joints at s = {} MPa (dashed: maximum hoop stress direction, -43.2 deg)".format(
        m.get("label", variant), "{:.3f}".format(stop / 1e6) if isinstance(stop, (int, float)) else "?"))
    for ax in axes:
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
    fig.tight_layout()
    fig.savefig(os.path.join(out, name), dpi=130)
    plt.close(fig)


def rosettes_figure(out, metrics):
    runs = {k: m for k, m in metrics.items() if k.startswith("r_b") and isinstance(m, dict)}
    if not runs:
        return
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
    colours = {15: "tab:blue", 45: "tab:red", 60: "tab:green"}
    aa = np.linspace(1.0, 5.5, 100)
    for beta in sorted({round(float(m["beta_deg"])) for m in runs.values()}):
        sel = sorted((m for m in runs.values() if round(float(m["beta_deg"])) == beta),
                     key=lambda m: float(m["half_length_m"]))
        a = [float(m["half_length_m"]) for m in sel]
        s = [(m.get("failure_stress_Pa") or {}).get("dda") for m in sel]
        s = [np.nan if v is None else v / 1e6 for v in s]
        k_ic = float(sel[0]["K_IC_Pa_sqrt_m"])
        c = colours.get(beta, "k")
        axes[0].plot(a, s, "o", color=c, label="DDA, beta = {} deg".format(beta))
        axes[0].plot(aa, k_ic / (math.cos(math.radians(beta)) * np.sqrt(np.pi * aa)) / 1e6, "-", color=c, lw=0.8)
        for m in sel:
            tips = m.get("tips", {})
            for side, marker in (("right", "o"), ("left", "x")):
                for ang in tips.get(side, {}).get("failed_joint_angles_deg", []):
                    axes[1].plot([beta + (0.8 if side == "left" else -0.8)], [ang], marker, color=c)
    bb = np.linspace(0.5, 89.5, 200)
    t = np.tan(np.radians(bb))
    hoop = np.degrees(2 * np.arctan((1 - np.sqrt(1 + 8 * t * t)) / (4 * t)))
    axes[1].plot(bb, hoop, "-", color="0.3", label="maximum hoop stress (Erdogan and Sih)")
    axes[1].fill_between(bb, hoop - 5, hoop + 5, color="0.85", label="target: within 5 deg")
    axes[1].plot([], [], "o", color="0.3", label="failed ray, right tip")
    axes[1].plot([], [], "x", color="0.3", label="failed ray, left tip")
    axes[0].set_xlabel("crack half-length a [m]")
    axes[0].set_ylabel("far-field stress at failure s [MPa]")
    axes[0].set_title("failure stress; lines: K_IC / (cos(beta) sqrt(pi a))")
    axes[0].set_xlim(0, 5.5)
    axes[0].grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    axes[1].set_xlabel("beta [deg]")
    axes[1].set_ylabel("kink angle in the tip's axes [deg]")
    axes[1].set_title("kink: rays at 5 deg steps around each tip")
    axes[1].set_xlim(0, 90)
    axes[1].grid(alpha=0.3)
    axes[1].legend(fontsize=8)
    fig.suptitle("Toughness criterion on tip rosettes (constrained Delaunay mesh), K_IC = 1.253 MPa m^0.5")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "lefm_mixed_rosettes.png"), dpi=130)
    plt.close(fig)


def main():
    out = sys.argv[1]
    with open(os.path.join(out, "result.json")) as f:
        result = json.load(f)
    metrics = result.get("metrics", {})
    if result.get("tier") == "quick":
        tips_figure(out, metrics, "quick", "lefm_mixed_tips_quick.png")
        return
    failure_stress_figure(out, load_csv(os.path.join(out, "failure_stress.csv")),
                          load_csv(os.path.join(out, "relations.csv")))
    tips_figure(out, metrics, "a3_t1", "lefm_mixed_tips.png")
    rosettes_figure(out, metrics)


if __name__ == "__main__":
    main()
