"""Figure of the Mode II LEFM case (seed Figure 4.8).

Usage: /usr/bin/python3 plot.py RESULT_DIR
(reads result.json and failure_stress.csv written there by verify_lefm_mode2)

Far-field shear at failure against the initial crack half-length a, one panel per
cohesion C0 (A: 1 MPa, B: 5 MPa), both joint lengths L: the DDA runs (markers), eq. 4.24
with N = 0, C0 sqrt(L / 2a) (dashed), and the exact-field relation C0 sqrt(L / (2a + L))
(solid). A last panel, when the study ran it: the toughness criterion at crack tips
(fracture.criterion: energy_release_rate) against K_IIC / sqrt(pi a). The full tier writes lefm_mode2.png, the quick tier lefm_mode2_quick.png.
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

STYLE = {0.5: ("o", "tab:blue"), 1.0: ("s", "tab:red")}


def plot_toughness(ax, rows):
    """Failure stress with the toughness criterion against K_IIC / sqrt(pi a)."""
    # The seed's one-diagonal mesh (variants *_two, reported) in grey crosses.
    one_diagonal = np.char.endswith(rows["variant"].astype(str), "_two")
    if one_diagonal.any():
        ax.plot(rows["a_m"][one_diagonal], rows["failure_stress_Pa"][one_diagonal] / 1e6, "x", color="0.5", ms=7,
                label="DDA, one diagonal per cell (reported)")
    rows = rows[~one_diagonal]
    delaunay = rows["delaunay_mesh"] if "delaunay_mesh" in rows.dtype.names else np.zeros(len(rows))
    groups = sorted(set((float(k), float(length), float(d)) for k, length, d in
                        zip(rows["K_IIC_Pa_sqrt_m"], rows["joint_length_m"], delaunay) if np.isfinite(length)))
    colours = ["tab:blue", "tab:red", "tab:green", "tab:purple", "tab:orange"]
    for i, (k, length, d) in enumerate(groups):
        sel = rows[(rows["K_IIC_Pa_sqrt_m"] == k) & (rows["joint_length_m"] == length) & (delaunay == d)]
        sel = sel[np.argsort(sel["a_m"])]
        marker = "D" if d == 1.0 else ("o" if length == 0.5 else "s")
        ax.plot(sel["a_m"], sel["failure_stress_Pa"] / 1e6, marker, color=colours[i % len(colours)], ms=7,
                mfc="none" if length == 1.0 and d != 1.0 else None,
                label=f"DDA, K_IIC = {k / 1e6:.3f} MPa m^0.5, L = {length:g} m" + (", Delaunay" if d == 1.0 else ""))
    for k in sorted(set(g[0] for g in groups)):
        a = np.linspace(0.5, 5.0, 200)
        ax.plot(a, k / np.sqrt(np.pi * a) / 1e6, "-", color="0.4", lw=0.8)
        ax.annotate(f"K_IIC / sqrt(pi a), {k / 1e6:.3f}", (a[-1], k / np.sqrt(np.pi * a[-1]) / 1e6), fontsize=7,
                    ha="right", va="bottom")
    ax.set_xlim(0.0, 5.5)
    ax.set_ylim(0.0, 1.0)
    ax.set_xlabel("initial crack half-length a [m]")
    ax.set_ylabel("far-field shear at failure [MPa]")
    ax.set_title("toughness criterion (energy release rate)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)


def main(result_dir):
    with open(os.path.join(result_dir, "result.json")) as f:
        tier = json.load(f).get("tier", "full")
    data = np.atleast_1d(np.genfromtxt(os.path.join(result_dir, "failure_stress.csv"), delimiter=",",
                                       names=True, dtype=None, encoding="utf-8"))
    tough = data[np.isfinite(data["K_IIC_Pa_sqrt_m"])] if "K_IIC_Pa_sqrt_m" in data.dtype.names else data[:0]
    if "K_IIC_Pa_sqrt_m" in data.dtype.names:
        data = data[~np.isfinite(data["K_IIC_Pa_sqrt_m"])]
    cohesions = sorted(set(float(c) for c in data["cohesion_Pa"] if np.isfinite(c)))
    panels = max(1, len(cohesions)) + (1 if len(tough) else 0)
    fig, axes = plt.subplots(1, panels, figsize=(6.0 * panels, 4.8), squeeze=False)
    if len(tough):
        plot_toughness(axes[0][-1], tough)
    for panel, (ax, c0) in enumerate(zip(axes[0], cohesions)):
        for length in sorted(set(float(v) for v in data["joint_length_m"] if np.isfinite(v))):
            rows = data[(data["cohesion_Pa"] == c0) & (data["joint_length_m"] == length)]
            rows = rows[np.argsort(rows["a_m"])]
            marker, colour = STYLE.get(length, ("^", "k"))
            a = np.linspace(0.0, max(5.0, float(rows["a_m"].max())), 300)
            ax.plot(a, c0 * np.sqrt(length / (2.0 * a + length)) / 1e6, "-", color=colour, lw=1,
                    label=f"C0 sqrt(L / (2a + L)), L = {length:g} m")
            with np.errstate(divide="ignore"):
                ax.plot(a[1:], c0 * np.sqrt(length / (2.0 * a[1:])) / 1e6, "--", color=colour, lw=1,
                        label=f"eq. 4.24, L = {length:g} m")
            ax.plot(rows["a_m"], rows["failure_stress_Pa"] / 1e6, marker, color=colour, ms=7,
                    label=f"DDA, L = {length:g} m")
        ax.set_ylim(0.0, 1.15 * c0 / 1e6)
        ax.set_xlabel("initial crack half-length a [m]")
        ax.set_ylabel("far-field shear at failure [MPa]")
        ax.set_title(f"{'AB'[panel]}: C0 = {c0 / 1e6:g} MPa")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Mode II failure stress, DDA vs eq. 4.24 and the exact-field relation (seed Fig. 4.8)")
    fig.tight_layout()
    name = "lefm_mode2.png" if tier == "full" else "lefm_mode2_quick.png"
    fig.savefig(os.path.join(result_dir, name), dpi=120)


if __name__ == "__main__":
    main(sys.argv[1])
