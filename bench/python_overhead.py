#!/usr/bin/env python3
"""Python's overhead (issue 22): caustica.render() against `caustica render` on the same scene at
the same spp and seed, same thread count. Each pair (CLI, then Python) repeats --repeat times; the
figure compared is the render's own time (the steps' seconds: the CLI's --stats-json `seconds`,
Python's Renderer.stats()["seconds"]), median over the repetitions; the whole call's wall time
(scene load, BVH build and, for the CLI, process start and image write included) is written too.

  PYTHONPATH=build/python python3 bench/python_overhead.py --binary build/caustica \\
      --scene scenes/cornell-box/scene.xml --res 128x128 --threads 1 --repeat 5 \\
      --case path:64 --case sppm:16 --csv bench/results/python_overhead.csv
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

from csv_out import write_csv

import caustica


def cli_render(args, integrator, spp, tmp):
    stats = os.path.join(tmp, "stats.json")
    cmd = [args.binary, "render", args.scene, "-q", "--checkpoint-every", "0", "-o", os.path.join(tmp, "cli.pfm"),
           "--integrator", integrator, "--spp", str(spp), "--seed", "1", "--threads", str(args.threads),
           "--res", args.res, "--stats-json", stats]
    start = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True)
    wall = time.perf_counter() - start
    with open(stats) as f:
        return json.load(f)["seconds"], wall


def python_render(args, integrator, spp):
    w, h = map(int, args.res.split("x"))
    start = time.perf_counter()
    scene = caustica.load_scene(args.scene)
    r = caustica.Renderer(scene, integrator=integrator, spp=spp, seed=1, threads=args.threads, resolution=(w, h))
    r.run()
    r.develop()
    wall = time.perf_counter() - start
    return r.stats()["seconds"], wall


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--binary", default="build/caustica")
    p.add_argument("--scene", default="scenes/cornell-box/scene.xml")
    p.add_argument("--res", default="128x128")
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument("--case", action="append", help="INTEGRATOR:SPP (repeatable)")
    p.add_argument("--csv", default="bench/results/python_overhead.csv")
    args = p.parse_args()
    cases = [(c.split(":")[0], int(c.split(":")[1])) for c in (args.case or ["path:64", "sppm:16"])]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for integrator, spp in cases:
            for rep in range(args.repeat):
                for runner in ("cli", "python"):
                    seconds, wall = (cli_render(args, integrator, spp, tmp) if runner == "cli"
                                     else python_render(args, integrator, spp))
                    rows.append(dict(integrator=integrator, spp=spp, res=args.res, threads=args.threads, rep=rep,
                                     runner=runner, render_seconds=round(seconds, 4), wall_seconds=round(wall, 4)))
    write_csv(args.csv, rows)
    print(f"{'integrator':10} {'spp':>5} {'cli s':>8} {'python s':>9} {'ratio':>7} {'cli wall':>9} {'py wall':>8}")
    for integrator, spp in cases:
        def med(runner, key):
            return statistics.median(r[key] for r in rows
                                     if r["integrator"] == integrator and r["runner"] == runner)
        cli, py = med("cli", "render_seconds"), med("python", "render_seconds")
        print(f"{integrator:10} {spp:5d} {cli:8.3f} {py:9.3f} {py / cli:7.4f} {med('cli', 'wall_seconds'):9.3f} "
              f"{med('python', 'wall_seconds'):8.3f}")


if __name__ == "__main__":
    sys.exit(main())
