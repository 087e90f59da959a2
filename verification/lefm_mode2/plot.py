"""Figure of the Mode II LEFM case (seed Figure 4.8).

Usage: /usr/bin/python3 plot.py RESULT_DIR
(reads result.json and failure_stress.csv written there by verify_lefm_mode2)

Far-field shear at failure against the initial crack half-length a, one panel per
cohesion C0 (A: 1 MPa, B: 5 MPa), both joint lengths L: the DDA runs (markers), eq. 4.24
with N = 0, C0 sqrt(L / 2a) (dashed), and the exact-field relation C0 sqrt(L / (2a + L))
(solid). The full tier writes lefm_mode2.png, the quick tier lefm_mode2_quick.png.
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

STYLE = {0.5: ("o", "tab:blue"), 1.0: ("s", "tab:red")}


def main(result_dir):
    with open(os.path.join(result_dir, "result.json")) as f:
        tier = json.load(f).get("tier", "full")
    data = np.atleast_1d(np.genfromtxt(os.path.join(result_dir, "failure_stress.csv"), delimiter=",",
                                       names=True, dtype=None, encoding="utf-8"))
    cohesions = sorted(set(float(c) for c in data["cohesion_Pa"] if np.isfinite(c)))
    fig, axes = plt.subplots(1, max(1, len(cohesions)), figsize=(6.0 * max(1, len(cohesions)), 4.8), squeeze=False)
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
