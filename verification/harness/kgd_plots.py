"""The KGD-type figure: three panels against time, A half-length l, B inlet (net)
pressure p0, C inlet width w0, with runs and self-similar solutions, as in seed
Figures 3.4-3.6 (M-vertex, verification/kgd) and 4.11-4.14 (K-vertex,
verification/kgd_toughness). Reads the files written through
verification/harness/kgd_series.hpp: series_<variant>.csv (runs) and analytical*.csv
(solutions); both name the columns half_length_m, inlet_net_pressure_Pa, inlet_width_m.

A case's plot.py builds a figure with panels(), draws solutions and runs in the order it
wants them in the legend (draw_solution, draw_run) and ends with finish().
"""
import plot_common  # first: selects the Agg backend

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

PANELS = [  # (column, scale, y label without the panel letter)
    ("half_length_m", 1.0, "half-length l [m]"),
    ("inlet_net_pressure_Pa", 1e-6, "inlet net pressure p0 [MPa]"),
    ("inlet_width_m", 1e3, "inlet width w0 [mm]"),
]
PRESSURE = 1  # index of the pressure panel


def panels():
    """A figure with the three panels side by side: (fig, axes)."""
    return plt.subplots(1, 3, figsize=(15, 4.6))


def variant_label(metrics, name, when):
    """The variant's label with its relative errors of l, p0, w0 at the end time
    (result.json "error_at_end"), `when` naming that time, or a note that the run did not
    complete."""
    m = metrics.get(name, {})
    label = m.get("label", name)
    err = m.get("error_at_end")
    if isinstance(err, dict):
        label += " ({}: l {:+.1f} %, p0 {:+.1f} %, w0 {:+.1f} %)".format(
            when, 100 * err["half_length"], 100 * err["inlet_net_pressure"], 100 * err["inlet_width"])
    elif m and not m.get("completed", False):
        label += " (did not complete)"
    return label


def draw_solution(axes, curve, label, **style):
    """A solution (analytical*.csv) on the three panels; black and thick unless `style` says otherwise."""
    style = {"color": "k", "lw": 2, **style}
    for ax, (column, scale, _) in zip(axes, PANELS):
        ax.plot(curve["time_s"], scale * curve[column], "-", label=label, **style)


def draw_run(axes, series, marker, label):
    """A run (series_<variant>.csv) on the three panels. The half-length moves in steps of
    one joint, so it is drawn as a staircase."""
    for ax, (column, scale, _) in zip(axes, PANELS):
        drawstyle = "steps-post" if column == "half_length_m" else "default"
        ax.plot(series["time_s"], scale * series[column], marker + "-", ms=4, lw=1, drawstyle=drawstyle,
                label=label)


def limit_pressure(ax, from_time_s, margin):
    """p0 ~ t^(-1/3) (M-vertex, K-vertex) is unbounded at t = 0: scale the pressure axis
    to the largest value drawn from `from_time_s` on, times `margin`."""
    top = []
    for line in ax.get_lines():
        x, y = np.asarray(line.get_xdata(), dtype=float), np.asarray(line.get_ydata(), dtype=float)
        late = (x >= from_time_s) & np.isfinite(y)
        if np.any(late):
            top.append(float(np.max(y[late])))
    if top:
        ax.set_ylim(0.0, margin * max(top))


def finish(fig, axes, result_dir, filename, title, plotted, pressure_from_s, pressure_margin,
           legend_axis, pressure_label=None):
    """Axis labels (panel letters A-C; `pressure_label` replaces the pressure panel's),
    the pressure axis range, the legend in the lower right of axes[legend_axis] (the
    curves rise from the lower left, and p0 and w0 of the M-vertex leave that corner
    empty too), the "no data" marker when no run was `plotted`, the title; writes the file."""
    for i, (ax, (_, _, ylabel)) in enumerate(zip(axes, PANELS)):
        if i == PRESSURE:
            limit_pressure(ax, pressure_from_s, pressure_margin)
            ylabel = pressure_label or ylabel
        ax.set_xlabel("time t [s]")
        ax.set_ylabel("ABC"[i] + ": " + ylabel)
        ax.grid(alpha=0.3)
    if axes[legend_axis].get_legend_handles_labels()[0]:
        axes[legend_axis].legend(fontsize=6.5, loc="lower right")
    if plotted == 0:
        plot_common.mark_no_data(axes)
    fig.suptitle(title)
    plot_common.save(fig, result_dir, filename)
