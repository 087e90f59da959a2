"""Figures of any HFDDA run directory: `hfdda plot DIR [--times T1,T2,...] [--out FIGDIR]`.

Run by the hfdda CLI with Debian's /usr/bin/python3 (matplotlib Agg, numpy). Writes
  FIGDIR/fracture_map_t<time>.png  the joints at the output step nearest each time (the
      last output if none is given), drawn like the figures of W. E. Morgan, PhD
      dissertation, Georgia Institute of Technology, 2014 (Figures 5.10-5.16): natural
      fractures thin black, joints with an open end thick dark grey, joints holding fluid
      without being open thick light grey;
  FIGDIR/histories.png  inlet pressure, opened and invaded lengths per joint kind, and the
      fluid mass check over time (the panels whose columns the run has);
  FIGDIR/iterations.png  for a run made with --trace-iterations (DIR/iterations.csv): every
      open-close iteration in order, its changes, the trial's worst joint overlap and block
      strain against the guards, the cycle holds and bonds broken, each attempt's end marked
      (grey: committed, red: refused and cut).
FIGDIR defaults to DIR/figures. Prints each file written. Exit 2 on a directory that is
not a run directory.
"""
import argparse
import csv
import glob
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection
except ImportError as e:  # pragma: no cover - depends on the machine
    sys.exit(f"hfdda plot: matplotlib is missing ({e}); install Debian's python3-matplotlib")


def fail(message):
    print(f"hfdda plot: {message}", file=sys.stderr)
    sys.exit(2)


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def joint_outputs(run_dir):
    """(step, path) of every joint CSV output, in step order."""
    out = []
    for path in glob.glob(os.path.join(run_dir, "joints", "joints_*.csv")):
        tag = os.path.basename(path)[len("joints_"):-len(".csv")]
        if tag.isdigit():
            out.append((int(tag), path))
    return sorted(out)


def draw_map(ax, rows, title, inlet):
    seg = lambda r: [(float(r["px"]), float(r["py"])), (float(r["qx"]), float(r["qy"]))]
    is_open = lambda r: "open" in (r["state_p"], r["state_q"])
    natural = [seg(r) for r in rows if r.get("natural") == "1"]
    opened = [seg(r) for r in rows if is_open(r)]
    invaded = [seg(r) for r in rows if r.get("fluid") == "1" and not is_open(r)]
    ax.add_collection(LineCollection(invaded, colors="0.75", linewidths=3.0))
    ax.add_collection(LineCollection(natural, colors="k", linewidths=0.6))
    ax.add_collection(LineCollection(opened, colors="0.25", linewidths=3.0))
    xs = [float(r[k]) for r in rows for k in ("px", "qx")]
    ys = [float(r[k]) for r in rows for k in ("py", "qy")]
    ax.set_xlim(min(xs), max(xs))
    ax.set_ylim(min(ys), max(ys))
    ax.set_aspect("equal")
    if inlet is not None:
        ax.plot([inlet[0]], [inlet[1]], "ko", mfc="none", ms=6)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(title, fontsize=9)
    return {"joints": len(rows), "natural": len(natural), "open": len(opened), "invaded": len(invaded)}


def main(argv):
    parser = argparse.ArgumentParser(prog="hfdda plot", description=__doc__.split("\n")[0])
    parser.add_argument("run_dir")
    parser.add_argument("--times", default="", help="comma-separated simulated times [s]")
    parser.add_argument("--out", default="", help="folder for the figures (default RUN_DIR/figures)")
    args = parser.parse_args(argv)
    run_dir = args.run_dir
    history_path = os.path.join(run_dir, "history.csv")
    outputs = joint_outputs(run_dir)
    if not os.path.isfile(history_path) or not outputs:
        fail(f"'{run_dir}' is not a run directory (needs history.csv and joints/joints_*.csv from `hfdda run`)")
    history = read_rows(history_path)
    time_of_step = {int(r["step"]): float(r["time_s"]) for r in history}
    time_of_step[0] = 0.0
    try:
        times = [float(t) for t in args.times.split(",") if t.strip()]
    except ValueError:
        fail(f"--times '{args.times}': give numbers separated by commas")
    out_dir = args.out or os.path.join(run_dir, "figures")
    os.makedirs(out_dir, exist_ok=True)

    inlet = None
    chosen = []
    for t in times or [time_of_step.get(outputs[-1][0], 0.0)]:
        step, path = min(outputs, key=lambda o: abs(time_of_step.get(o[0], 0.0) - t))
        if (step, path) not in chosen:
            chosen.append((step, path))
    for step, path in chosen:
        t = time_of_step.get(step, 0.0)
        fig, ax = plt.subplots(figsize=(6, 6))
        counts = draw_map(ax, read_rows(path),
                          f"{os.path.basename(os.path.normpath(run_dir))}: t = {t:g} s (step {step})", inlet)
        name = os.path.join(out_dir, f"fracture_map_t{t:g}.png")
        fig.tight_layout()
        fig.savefig(name, dpi=120)
        plt.close(fig)
        print(name)
        # What the map shows, so that a reader (or a test) need not open the picture.
        print(f"  t = {t:g} s: {counts['joints']} joints drawn: {counts['natural']} natural (thin), "
              f"{counts['open']} open (thick), {counts['invaded']} closed with fluid (light)")

    columns = history[0].keys() if history else []
    time = [float(r["time_s"]) for r in history]
    panels = []
    if "injection_pressure_Pa" in columns:
        panels.append(("inlet pressure [MPa]", [("injection_pressure_Pa", 1e-6, "inlet")]))
    lengths = [(c, 1.0, c.replace("_length", "").replace("_m", "")) for c in
               ("opened_length_rock_m", "opened_length_natural_m", "invaded_length_rock_m", "invaded_length_natural_m",
                "slipped_length_natural_m") if c in columns]
    if lengths:
        panels.append(("length [m]", lengths))
    ledger = [(c, 1.0, c.replace("mass_", "").replace("_kg", "")) for c in
              ("mass_injected_kg", "mass_stored_kg", "mass_vented_kg", "mass_leaked_kg") if c in columns]
    if ledger:
        panels.append(("fluid mass [kg]", ledger))
    if "mass_volume_error" in columns:
        panels.append(("relative mass error [-]", [("mass_volume_error", 1.0, "volume check"),
                                                  ("mass_balance_error", 1.0, "ledger")]))
    if panels and history:
        fig, axes = plt.subplots(len(panels), 1, figsize=(7, 2.6 * len(panels)), sharex=True, squeeze=False)
        for ax, (label, series) in zip(axes[:, 0], panels):
            for column, scale, name in series:
                if column in columns:
                    ax.plot(time, [float(r[column]) * scale for r in history], label=name)
            ax.set_ylabel(label)
            ax.legend(fontsize=7)
        axes[-1, 0].set_xlabel("time [s]")
        name = os.path.join(out_dir, "histories.png")
        fig.tight_layout()
        fig.savefig(name, dpi=120)
        plt.close(fig)
        print(name)
    iterations_path = os.path.join(run_dir, "iterations.csv")
    if os.path.isfile(iterations_path):
        name = draw_iterations(read_rows(iterations_path), out_dir)
        if name:
            print(name)
    return 0


def draw_iterations(rows, out_dir):
    """iterations.png from the rows of iterations.csv; None if it holds no iteration."""
    its = [r for r in rows if r["row"] == "iteration"]
    if not its:
        return None
    x = list(range(1, len(its) + 1))
    value = lambda column: [float(r[column]) for r in its]
    fig, axes = plt.subplots(3, 1, figsize=(9, 7.5), sharex=True)
    axes[0].plot(x, value("contact_changes"), lw=0.8, label="contact changes")
    axes[0].plot(x, value("coupled_changes"), lw=0.8, label="fluid changes")
    axes[0].set_yscale("symlog", linthresh=1.0)
    axes[0].set_ylabel("changes applied")
    floor = 1e-12  # log axes: a zero is drawn at the floor
    axes[1].semilogy(x, [max(v, floor) for v in value("overlap_fraction")], lw=0.8, label="joint overlap / joint length")
    axes[1].semilogy(x, [max(v, floor) for v in value("block_strain")], lw=0.8, label="block strain")
    axes[1].axhline(0.1, color="r", ls="--", lw=0.6, label="guards (0.1)")
    axes[1].set_ylabel("trial's worst")
    axes[2].plot(x, value("cycle_holds"), lw=0.8, label="cycle holds")
    axes[2].plot(x, value("bonds_broken"), lw=0.8, label="bonds broken")
    axes[2].set_ylabel("in the attempt so far")
    # Attempt ends: after the last iteration row that precedes each attempt row.
    count = 0
    for r in rows:
        if r["row"] == "iteration":
            count += 1
        elif count > 0:
            refused = r["text"] != "committed"
            for ax in axes:
                ax.axvline(count + 0.5, color="r" if refused else "0.8", lw=0.8 if refused else 0.4, zorder=0)
    for ax in axes:
        ax.legend(fontsize=7, loc="upper left")
    steps = sorted({int(r["step"]) for r in its})
    axes[-1].set_xlabel(f"open-close iteration, in order (steps {steps[0]}-{steps[-1]})")
    name = os.path.join(out_dir, "iterations.png")
    fig.tight_layout()
    fig.savefig(name, dpi=120)
    plt.close(fig)
    return name


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
