"""Figures of the KGD toughness-storage case (seed Figures 4.11-4.14).

Usage: /usr/bin/python3 plot.py RESULT_DIR
(reads result.json, series_<variant>.csv and analytical_<variant>.csv written there by
verify_kgd_toughness)

Each figure has three panels against time, as in the seed: A half-length, B inlet
pressure (net: there is no background stress), C inlet width, with the K-vertex solution
of each variant's toughness (analytical_<variant>.csv, computed by the driver from
solver/analytical/kgd.hpp, so the plot and the checks share one formula). Variants with
the same K_IC share one curve. The panels are drawn by verification/harness/kgd_plots.py,
shared with the viscosity case.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "harness"))
import kgd_plots  # noqa: E402
import plot_common  # noqa: E402

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
        ("kgd_toughness_energy_t1.png",
         "KGD toughness storage, toughness criterion at crack tips, K_IC = 0.886 and 1.253 MPa m^0.5",
         [("l05_t1_energy", "o"), ("l1_k0886_energy", "x"), ("l1_t1_energy", "s"), ("l1_t1_energy_large", "^")]),
        ("kgd_toughness_energy_t5.png",
         "KGD toughness storage, toughness criterion at crack tips, K_IC = 4.43 and 6.27 MPa m^0.5",
         [("l05_t5_energy", "o"), ("l1_t5_energy", "s")]),
        ("kgd_toughness_energy_large_t1.png",
         "Toughness criterion, 800 m x 720 m plate (K-vertex's), K_IC = 0.886 and 1.253 MPa m^0.5",
         [("l05_t1_energy_large", "o"), ("l1_k0886_energy_large", "x"), ("l1_t1_energy_large", "s")]),
        ("kgd_toughness_energy_large_t5.png",
         "Toughness criterion, 800 m x 720 m plate (K-vertex's), K_IC = 4.43 and 6.27 MPa m^0.5",
         [("l05_t5_energy_large", "o"), ("l1_t5_energy_large", "s")]),
        ("kgd_toughness_energy_slow.png",
         "Toughness criterion in the K-vertex's regime (Q0 / 1000, K_m = 16-23), 800 m x 720 m plate",
         [("l05_t1_energy_slow", "o"), ("l1_k0886_energy_slow", "x"), ("l1_t1_energy_slow", "s")]),
    ],
    "quick": [
        ("kgd_toughness_quick.png", "KGD toughness storage, quick tier: L = 1 m, T0 = 1 MPa",
         [("quick", "s")]),
    ],
}


def figure(result_dir, metrics, filename, title, variants):
    fig, axes = kgd_plots.panels()
    plotted = 0
    drawn_k = []  # toughness of the solutions drawn, so a shared curve is drawn once
    for name, marker in variants:
        series = plot_common.load_csv(os.path.join(result_dir, f"series_{name}.csv"))
        exact = plot_common.load_csv(os.path.join(result_dir, f"analytical_{name}.csv"))
        kic = metrics.get(name, {}).get("fracture_toughness_Pa_sqrt_m")
        if exact is not None and kic is not None and all(abs(kic - k) > 1e-3 * k for k in drawn_k):
            drawn_k.append(kic)
            kgd_plots.draw_solution(axes, exact, "K-vertex, K_IC = {:.3g} MPa m^0.5".format(kic * 1e-6),
                                    alpha=1.0 if len(drawn_k) == 1 else 0.5)
        if series is not None:
            kgd_plots.draw_run(axes, series, marker, kgd_plots.variant_label(metrics, name, "end"))
            plotted += 1
    # p0 range from a tenth of the run on (t = 1 s of the seed's 10 s); the legend where the
    # curves rise from the lower left.
    end_s = max((metrics.get(name, {}).get("time_reached_s") or 10.0) for name, _ in variants)
    kgd_plots.finish(fig, axes, result_dir, filename, title, plotted, pressure_from_s=0.1 * end_s, pressure_margin=1.3,
                     legend_axis=0, pressure_label="inlet pressure p0 [MPa]")


def main(result_dir):
    tier, metrics = plot_common.read_result(result_dir)
    for filename, title, variants in plot_common.for_tier(FIGURES, tier):
        figure(result_dir, metrics, filename, title, variants)


if __name__ == "__main__":
    main(sys.argv[1])
