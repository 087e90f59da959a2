"""Figure of a generated fracture network: `hfdda network CASE --out DIR` runs
`hfdda_network_plot.py DIR --domain XMIN,XMAX,YMIN,YMAX [--title TEXT]`.

Run by the hfdda CLI with Debian's /usr/bin/python3 (matplotlib Agg). Reads
DIR/network.csv (one row per joint of a generated fracture: fracture, set, joint,
x1, y1, x2, y2) and writes DIR/network.png: the fractures of each set in their own
colour inside the outline of the domain, like Figures 5.6-5.9 of W. E. Morgan, PhD
dissertation, Georgia Institute of Technology, 2014. Prints the file written. Exit 2
when DIR has no network.csv or the arguments are wrong.
"""
import argparse
import csv
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection
except ImportError as e:  # pragma: no cover - depends on the machine
    print(f"hfdda network: matplotlib is missing ({e}); install Debian's python3-matplotlib", file=sys.stderr)
    sys.exit(2)


def fail(message):
    print(f"hfdda network: {message}", file=sys.stderr)
    sys.exit(2)


def main():
    parser = argparse.ArgumentParser(description="draw DIR/network.csv as DIR/network.png")
    parser.add_argument("dir")
    parser.add_argument("--domain", required=True, help="xmin,xmax,ymin,ymax of the domain [m]")
    parser.add_argument("--title", default="")
    args = parser.parse_args()
    path = os.path.join(args.dir, "network.csv")
    if not os.path.isfile(path):
        fail(f"{path} not found")
    try:
        xmin, xmax, ymin, ymax = (float(v) for v in args.domain.split(","))
    except ValueError:
        fail(f"--domain needs xmin,xmax,ymin,ymax (got '{args.domain}')")

    segments = {}  # set name -> segments, in the order the sets first appear
    fractures = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            seg = [(float(row["x1"]), float(row["y1"])), (float(row["x2"]), float(row["y2"]))]
            segments.setdefault(row["set"], []).append(seg)
            fractures.setdefault(row["set"], set()).add(row["fracture"])

    fig, ax = plt.subplots(figsize=(6.5, 6.5 * (ymax - ymin) / (xmax - xmin)))
    ax.plot([xmin, xmax, xmax, xmin, xmin], [ymin, ymin, ymax, ymax, ymin], color="0.5", linewidth=0.8)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, (name, segs) in enumerate(segments.items()):
        ax.add_collection(LineCollection(segs, colors=colours[i % len(colours)], linewidths=1.2,
                                         label=f"{name}: {len(fractures[name])} fractures"))
    ax.set_xlim(xmin, xmax)
    ax.set_ylim(ymin, ymax)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    if args.title:
        ax.set_title(args.title, fontsize=9)
    if segments:
        ax.legend(loc="upper right", fontsize=8, framealpha=0.9)
    out = os.path.join(args.dir, "network.png")
    fig.savefig(out, dpi=150, bbox_inches="tight")
    print(out)


if __name__ == "__main__":
    main()
