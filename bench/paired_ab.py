#!/usr/bin/env python3
"""Two settings of `caustica render` against each other in paired runs, writing CSV.

On a shared VM whole renders move by 10-50% from one minute to the next (other guests), so two
settings timed in separate series can swap places. Here each pair runs A and B back to back (the
order alternating from pair to pair) and keeps the ratio B / A of their `run_seconds`; the median
of the ratios over N pairs is the figure, robust to the drift that moves both runs of a pair
alike. Reported per scene: the median seconds of A and of B, the median, smallest and largest
ratio B / A (> 1: A is faster).

Example (Embree's instruction sets, docs/PERFORMANCE.md 2026-11-28):
  bench/paired_ab.py --caustica build/caustica --scenes cornell-water,cornell-box --pairs 8 \\
      --common '--res 128x128 --spp 32 -D max_depth=16 --threads 2' \\
      --a '--embree-isa sse4.2' --b '--embree-isa widest' --csv out/isa.csv

Two builds against each other (a change measured before it lands): --caustica is A's binary,
--caustica-b B's; --a and --b may then be empty.
"""
import argparse
import json
import os
import shlex
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, '..'))
sys.path.insert(0, HERE)
from csv_out import write_csv  # noqa: E402


def scene_path(name):
    """A name of scenes/NAME/scene.xml, or a path."""
    bundled = os.path.join(ROOT, 'scenes', name, 'scene.xml')
    return bundled if os.path.exists(bundled) else name


def run_seconds(caustica, scene, args, tmp):
    stats = os.path.join(tmp, 'stats.json')
    cmd = [caustica, 'render', scene, '--stats-json', stats, '-q', '-o', os.path.join(tmp, 'image.pfm')] + args
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit('paired_ab: ' + ' '.join(cmd) + ' failed: ' + done.stderr.strip())
    with open(stats) as f:
        return json.load(f)['run_seconds']


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--caustica', default=os.path.join(ROOT, 'build', 'caustica'))
    p.add_argument('--caustica-b', help='binary of setting B (default: --caustica), to time a build against another')
    p.add_argument('--scenes', default='cornell-water', help='comma separated names in scenes/ or XML paths')
    p.add_argument('--pairs', type=int, default=8)
    p.add_argument('--common', default='', help='arguments of every run')
    p.add_argument('--a', default='', help='arguments of setting A')
    p.add_argument('--b', default='', help='arguments of setting B')
    p.add_argument('--csv')
    o = p.parse_args()
    if o.pairs < 1:
        sys.exit('paired_ab: --pairs must be at least 1')
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in o.scenes.split(','):
            scene = scene_path(name)
            a_args = shlex.split(o.common) + shlex.split(o.a)
            b_args = shlex.split(o.common) + shlex.split(o.b)
            bin_a, bin_b = o.caustica, o.caustica_b or o.caustica
            ta, tb = [], []
            for i in range(o.pairs):
                if i % 2 == 0:
                    ta.append(run_seconds(bin_a, scene, a_args, tmp))
                    tb.append(run_seconds(bin_b, scene, b_args, tmp))
                else:
                    tb.append(run_seconds(bin_b, scene, b_args, tmp))
                    ta.append(run_seconds(bin_a, scene, a_args, tmp))
            ratios = [y / x for x, y in zip(ta, tb)]
            row = {'scene': name, 'common': o.common, 'a': o.a, 'b': o.b, 'binary_a': bin_a, 'binary_b': bin_b,
                   'pairs': o.pairs,
                   'median_a_s': round(statistics.median(ta), 4), 'median_b_s': round(statistics.median(tb), 4),
                   'median_b_over_a': round(statistics.median(ratios), 4), 'min_b_over_a': round(min(ratios), 4),
                   'max_b_over_a': round(max(ratios), 4)}
            rows.append(row)
            print(f"{name:16s} A {row['median_a_s']:.3f} s  B {row['median_b_s']:.3f} s  B/A median "
                  f"{row['median_b_over_a']:.3f} (min {row['min_b_over_a']:.3f}, max {row['max_b_over_a']:.3f})",
                  flush=True)
    if o.csv:
        write_csv(o.csv, rows)


if __name__ == '__main__':
    main()
