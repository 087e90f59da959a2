"""Figures of the KGD viscosity-storage case (seed Figures 3.4-3.6).

Usage: /usr/bin/python3 plot.py RESULT_DIR
(reads result.json, series_<variant>.csv and analytical.csv written there by verify_kgd)

Each figure has three panels against time: A half-length, B inlet net pressure,
C inlet width, with the M-vertex solution (analytical.csv, computed by the driver from
solver/analytical/kgd.hpp, so the plot and the checks share one formula). The panels
are drawn by verification/harness/kgd_plots.py, shared with the toughness case.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "harness"))
import kgd_plots  # noqa: E402
import plot_common  # noqa: E402

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


def figure(result_dir, metrics, analytical, filename, title, variants):
    fig, axes = kgd_plots.panels()
    if analytical is not None:
        kgd_plots.draw_solution(axes, analytical, "M-vertex (zero toughness, no leak-off)")
    plotted = 0
    for name, marker in variants:
        series = plot_common.load_csv(os.path.join(result_dir, f"series_{name}.csv"))
        if series is None:
            continue
        kgd_plots.draw_run(axes, series, marker, kgd_plots.variant_label(metrics, name, "10 s"))
        plotted += 1
    # p0 range: the data and the solution from the first quarter second on; the legend
    # in the emptiest corner of the three panels.
    kgd_plots.finish(fig, axes, result_dir, filename, title, plotted, pressure_from_s=0.25, pressure_margin=1.15,
                     legend_axis=2)


def main(result_dir):
    tier, metrics = plot_common.read_result(result_dir)
    analytical = plot_common.load_csv(os.path.join(result_dir, "analytical.csv"))
    for filename, title, variants in plot_common.for_tier(FIGURES, tier):
        figure(result_dir, metrics, analytical, filename, title, variants)


if __name__ == "__main__":
    main(sys.argv[1])
