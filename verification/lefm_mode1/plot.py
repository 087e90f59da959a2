"""Figure of the Mode I LEFM study (seed Figure 4.6).

Usage: /usr/bin/python3 plot.py RESULT_DIR
(reads failure_stress.csv written there by verify_lefm_mode1)

One panel per tensile strength T0, as in the seed: the far-field tension at complete
failure against the initial half-length a, for L = 0.5 and 1 m, with the exact-field
relation T0 sqrt(L / (2a + L)) (erratum 6) and the seed's eq. 4.14, T0 sqrt(L / 2a).
Open markers: the level at which the first whole joint failed. A last panel, when the
study ran it: the toughness criterion at crack tips (fracture.criterion:
energy_release_rate) against the LEFM relation K_IC / sqrt(pi a), for each K_IC, L and mesh
(structured, or constrained Delaunay).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def plot_toughness(ax, rows):
    """Failure stress with the toughness criterion against K_IC / sqrt(pi a)."""
    def mesh(r):
        return r.get("mesh") or "structured"

    groups = sorted({(float(r["K_IC_Pa_sqrt_m"]), float(r["L_m"]), mesh(r)) for r in rows})
    colours = ["tab:blue", "tab:red", "tab:green", "tab:purple", "tab:orange", "tab:brown"]
    markers = {0.25: "^", 0.5: "o", 1.0: "s"}
    for i, (k, length, kind) in enumerate(groups):
        sel = sorted((r for r in rows if float(r["K_IC_Pa_sqrt_m"]) == k and float(r["L_m"]) == length
                      and mesh(r) == kind), key=lambda r: float(r["a_m"]))
        a = np.array([float(r["a_m"]) for r in sel])
        fail = np.array([float(r["failure_Pa"]) if r["failure_Pa"] not in ("nan", "") else np.nan for r in sel])
        marker = "D" if kind == "delaunay" else markers.get(length, "o")
        ax.plot(a, fail / 1e6, marker, mfc="none" if length == 1.0 and kind != "delaunay" else None,
                color=colours[i % len(colours)],
                label=f"DDA, K_IC = {k / 1e6:.3f} MPa m^0.5, L = {length} m" + (", Delaunay" if kind == "delaunay" else ""))
    for k in sorted({g[0] for g in groups}):
        aa = np.linspace(0.5, 5.0, 200)
        ax.plot(aa, k / np.sqrt(np.pi * aa) / 1e6, "-", color="0.4", lw=0.8)
        ax.annotate(f"K_IC / sqrt(pi a), {k / 1e6:.3f}", (aa[-1], k / np.sqrt(np.pi * aa[-1]) / 1e6),
                    fontsize=7, ha="right", va="bottom")
    ax.set_title("toughness criterion (energy release rate)")
    ax.set_xlabel("initial half-length a [m]")
    ax.set_ylabel("far-field tension at failure [MPa]")
    ax.set_xlim(0, 5.5)
    ax.set_ylim(0, 1.0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)


def main(result_dir):
    with open(os.path.join(result_dir, "failure_stress.csv")) as f:
        all_rows = list(csv.DictReader(f))

    def energy(r):
        return r.get("K_IC_Pa_sqrt_m", "nan") not in ("nan", "")

    rows = [r for r in all_rows if not energy(r)]
    tough = [r for r in all_rows if energy(r)]
    strengths = sorted({float(r["T0_Pa"]) for r in rows})
    panels = len(strengths) + (1 if tough else 0)
    fig, axes = plt.subplots(1, panels, figsize=(6 * panels, 4.5), squeeze=False)
    if tough:
        plot_toughness(axes[0][-1], tough)
    for ax, t0 in zip(axes[0], strengths):
        for length, colour in ((0.5, "tab:blue"), (1.0, "tab:red")):
            sel = sorted((r for r in rows if float(r["T0_Pa"]) == t0 and float(r["L_m"]) == length),
                         key=lambda r: float(r["a_m"]))
            if not sel:
                continue
            a = np.array([float(r["a_m"]) for r in sel])
            fail = np.array([float(r["failure_Pa"]) if r["failure_Pa"] not in ("nan", "") else np.nan for r in sel])
            joint = np.array([float(r["first_joint_failure_Pa"]) if r["first_joint_failure_Pa"] not in ("nan", "")
                              else np.nan for r in sel])
            ax.plot(a, fail / 1e6, "o", color=colour, label=f"DDA, L = {length} m: complete failure")
            ax.plot(a, joint / 1e6, "o", mfc="none", color=colour, label=f"DDA, L = {length} m: first joint")
            aa = np.linspace(0.0, 5.0, 201)
            ax.plot(aa, t0 * np.sqrt(length / (2 * aa + length)) / 1e6, "-", color=colour,
                    label=f"T0 sqrt(L/(2a+L)), L = {length} m")
            ap = aa[aa > 0.2]
            ax.plot(ap, t0 * np.sqrt(length / (2 * ap)) / 1e6, ":", color=colour, label=f"eq. 4.14, L = {length} m")
        ax.set_title(f"T0 = {t0 / 1e6:g} MPa")
        ax.set_xlabel("initial half-length a [m]")
        ax.set_ylabel("far-field tension at failure [MPa]")
        ax.set_ylim(0, 1.2 * t0 / 1e6)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Mode I: failure stress of a centre crack (seed Fig. 4.6)")
    fig.tight_layout()
    fig.savefig(os.path.join(result_dir, "lefm_mode1.png"), dpi=110)


if __name__ == "__main__":
    main(sys.argv[1])
