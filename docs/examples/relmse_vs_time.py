#!/usr/bin/env python3
"""relMSE against rendering time for path, mlt and sppm on a bundled caustic scene (docs/PYTHON.md).

Renders scenes/glass-caustic at 64x64 with each integrator at several time budgets, compares every
image with the bundled reference (scenes/glass-caustic/reference/glass-caustic-64.exr: Mitsuba 3,
262144 spp) using caustica's relMSE (caustica.compare, as `caustica compare`), and plots relMSE
against the render's own seconds on log-log axes.

  PYTHONPATH=build/python python3 docs/examples/relmse_vs_time.py --budgets 1 2 4 8 \\
      --threads 2 --png docs/img/python-relmse-vs-time.png --csv out/relmse-vs-time.csv
"""
import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt

import caustica

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
SCENE = os.path.join(ROOT, "scenes", "glass-caustic", "scene.xml")
REFERENCE = os.path.join(ROOT, "scenes", "glass-caustic", "reference", "glass-caustic-64.exr")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--budgets", type=float, nargs="+", default=[1, 2, 4, 8], help="seconds per render")
    p.add_argument("--integrators", nargs="+", default=["path", "mlt", "sppm"])
    p.add_argument("--threads", type=int, default=None, help="worker threads (default: all cores)")
    p.add_argument("--png", default="relmse-vs-time.png")
    p.add_argument("--csv", default=None)
    args = p.parse_args()

    scene = caustica.load_scene(SCENE, width=64, height=64)  # one scene, copied by every render
    reference = caustica.read_image(REFERENCE)
    rows = []
    for integrator in args.integrators:
        for budget in args.budgets:
            r = caustica.Renderer(scene, integrator=integrator, time=budget, seed=1, threads=args.threads)
            r.run()
            stats = r.stats()
            error = caustica.compare(r.develop(), reference)
            rows.append(dict(integrator=integrator, budget=budget, seconds=stats["seconds"], spp=stats["spp"],
                             relmse=error["relmse"], worst_share=error["relmse_worst_share"],
                             mean_ratio=error["mean_ratio"]))
            print(f"{integrator:5} {budget:6.2f} s budget: {stats['seconds']:6.2f} s, {stats['spp']:6d} spp, "
                  f"relMSE {error['relmse']:.4g} (worst 1% of pixels: {100 * error['relmse_worst_share']:.0f}%), "
                  f"mean/ref {error['mean_ratio']:.4f}", flush=True)

    if args.csv:
        os.makedirs(os.path.dirname(os.path.abspath(args.csv)), exist_ok=True)
        with open(args.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for integrator in args.integrators:
        mine = [r for r in rows if r["integrator"] == integrator]
        ax.loglog([r["seconds"] for r in mine], [r["relmse"] for r in mine], "o-", label=integrator)
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("relMSE vs reference")
    ax.set_title("glass-caustic 64x64" + (f", {args.threads} threads" if args.threads else ""))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.png, dpi=120)
    print("wrote", args.png)


if __name__ == "__main__":
    main()
