"""Figures of the Griffith case (seed Figure 3.2 and a convergence view).

Usage: /usr/bin/python3 plot.py RESULT_DIR   (reads profile_*.csv and result.json there)
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def load(result_dir, name):
    path = os.path.join(result_dir, f"profile_{name}.csv")
    if not os.path.exists(path):
        return None
    return np.genfromtxt(path, delimiter=",", names=True)


def main(result_dir):
    with open(os.path.join(result_dir, "result.json")) as f:
        result = json.load(f)
    metrics = result["metrics"]

    fig, ax = plt.subplots(figsize=(7, 4.5))
    exact = load(result_dir, "tri4_alm")
    x = np.linspace(exact["x_m"].min(), exact["x_m"].max(), 400)
    peak = metrics["exact_peak_width_m"]
    half = exact["x_m"].max()
    ax.plot(x, 1e3 * peak * np.sqrt(np.clip(1 - (x / half) ** 2, 0, None)), "k-", lw=2, label="eq. 3.1 (infinite plane)")
    styles = {"tri4_alm": "o-", "tri4_penalty": "s--", "tri2_alm": "^-", "tri2_penalty": "v--",
              "quad_alm": "D-", "quad_penalty": "x--"}
    for name, style in styles.items():
        p = load(result_dir, name)
        if p is not None:
            ax.plot(p["x_m"], 1e3 * p["w_m"], style, ms=4, label=f"{metrics[name]['label']} "
                    f"(max err {100 * metrics[name]['max_error_over_peak']:.1f} %)")
    ax.set_xlabel("distance along the crack x [m]")
    ax.set_ylabel("opening w [mm]")
    ax.set_title("Griffith crack, seed geometry (100 m domain, 1 m joints)")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(result_dir, "griffith_profiles.png"), dpi=130)

    if result["tier"] == "full":
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for name in ["tri4_alm", "domain200_tri4_alm", "domain400_tri4_alm", "domain400_h05_tri4_alm"]:
            p = load(result_dir, name)
            if p is not None:
                ax.plot(p["x_m"], 100 * (p["w_m"] - p["w_exact_m"]) / peak, "o-", ms=3,
                        label=f"{metrics[name]['label'] if name != 'tri4_alm' else '100 m domain, 1 m cells, ALM'}")
        ax.axhline(3, color="r", ls=":", label="3 % target")
        ax.axhline(-3, color="r", ls=":")
        ax.set_xlabel("distance along the crack x [m]")
        ax.set_ylabel("(w - w_exact) / w_exact(0) [%]")
        ax.set_title("Error sources: domain truncation (+) and tip resolution (-)")
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(result_dir, "griffith_convergence.png"), dpi=130)


if __name__ == "__main__":
    main(sys.argv[1])
