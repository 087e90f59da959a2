"""Figures of the fracture-network cases (seed 5.3, Figures 5.10-5.16).

Usage: /usr/bin/python3 plot.py RESULT_DIR
(reads result.json, patterns.csv and joints_<variant>.csv written there by verify_networks)

Drawn like the seed's figures: natural fractures thin black, open joints thick dark grey,
joints invaded by fluid without being open lighter thick grey, the injection point as a
circle; the 250 m reservoir on the initial mesh. networks_quick.png: the quick run.
networks_patterns.png: the two networks at dsigma = 0 and 12 MPa (Figures 5.10-5.13).
networks_fluid.png: 100 mPa s at both stresses and 2 kg/s at dt = 30 s (Figures 5.14-5.16).
networks_roundoff.png: each base run beside its round-off twin (rate x (1 + 1e-12)).
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "harness"))
import plot_common  # noqa: E402  (first: selects the Agg backend)
from pattern_plots import panels, rows  # noqa: E402


def main(result_dir):
    tier, _ = plot_common.read_result(result_dir)
    summary = {r["variant"]: r for r in rows(os.path.join(result_dir, "patterns.csv"))}
    if tier == "quick":
        panels(result_dir, summary, [("n45_s12_quick", "sets 45/135, dsigma = 12 MPa, t = 10 min")],
               "networks_quick.png", 1)
        return
    panels(result_dir, summary,
           [("n45_s0", "sets 45/135, dsigma = 0 (seed Fig. 5.10)"), ("n0_s0", "sets 0/90, dsigma = 0 (Fig. 5.11)"),
            ("n45_s12", "sets 45/135, dsigma = 12 MPa (Fig. 5.12)"), ("n0_s12", "sets 0/90, dsigma = 12 MPa (Fig. 5.13)")],
           "networks_patterns.png", 2)
    panels(result_dir, summary,
           [("n45_s0", "20 mPa s, 1 kg/s, dsigma = 0"), ("n45_s0_mu100", "100 mPa s, dsigma = 0 (Fig. 5.14)"),
            ("n45_s0_q2", "2 kg/s, dt = 30 s, 30 min (Fig. 5.16)"),
            ("n45_s12", "20 mPa s, 1 kg/s, dsigma = 12 MPa"), ("n45_s12_mu100", "100 mPa s, dsigma = 12 MPa (Fig. 5.15)")],
           "networks_fluid.png", 3)
    twins = [(base, title) for base, title in
             [("n45_s0", "sets 45/135, dsigma = 0"), ("n45_s12", "sets 45/135, dsigma = 12 MPa"),
              ("n0_s0", "sets 0/90, dsigma = 0"), ("n0_s12", "sets 0/90, dsigma = 12 MPa")]
             if base + "_twin" in summary]
    if twins:
        pairs = []
        for base, title in twins:
            pairs += [(base, title), (base + "_twin", title + ", rate x (1 + 1e-12)")]
        panels(result_dir, summary, pairs, "networks_roundoff.png", 2)


if __name__ == "__main__":
    main(sys.argv[1])
