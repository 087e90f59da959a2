"""Figure of the Marcellus case (seed 5.4, Figure 5.19).

Usage: /usr/bin/python3 plot.py RESULT_DIR
(reads result.json and joints_<variant>.csv written there by verify_marcellus)

marcellus_quick.png / marcellus.png: the 250 m region at the end of the run, drawn like the
seed's figure (harness/pattern_plots.py), with the open and invaded band widths; in the
full tier beside it the round-off twin (the rate x (1 + 1e-12)).
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "harness"))
import plot_common  # noqa: E402  (first: selects the Agg backend)
from pattern_plots import panels  # noqa: E402


def main(result_dir):
    tier, metrics = plot_common.read_result(result_dir)
    variant = "marcellus_quick" if tier == "quick" else "marcellus"
    m = metrics.get(variant, {}) if isinstance(metrics, dict) else {}
    title = "Marcellus shale, " + ("first 10 min" if tier == "quick" else "1 h (seed Fig. 5.19)")
    if m.get("completed") is False and m.get("time_s") is not None:
        title += f", stopped at t = {m['time_s']:.0f} s"
    if m.get("open_y_extent_m") is not None and m.get("invaded_y_extent_m") is not None:
        title += f"\nopen band {m['open_y_extent_m']:.0f} m wide, invaded band {m['invaded_y_extent_m']:.0f} m"
    entries = [(variant, title)]
    twin = metrics.get("marcellus_twin") if isinstance(metrics, dict) and tier != "quick" else None
    if twin:
        twin_title = "the same, rate x (1 + 1e-12)"
        if twin.get("completed") is False and twin.get("time_s") is not None:
            twin_title += f", stopped at t = {twin['time_s']:.0f} s"
        if twin.get("open_similarity") is not None:
            twin_title += f"\nopen set {twin['open_similarity']:.2f} similar (Jaccard)"
        entries.append(("marcellus_twin", twin_title))
    panels(result_dir, {}, entries, "marcellus_quick.png" if tier == "quick" else "marcellus.png", len(entries))


if __name__ == "__main__":
    main(sys.argv[1])
