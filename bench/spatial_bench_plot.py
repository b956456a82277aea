#!/usr/bin/env python3
"""Plots a CSV of build/spatial_bench (bench/results/spatial-*.csv) as one PNG:

  - one panel per point set (uniform/points, cornell-water/spheres, ...): grouped bars of
    queries/s (log scale), one group per query type, one bar per structure;
  - a last row with build time (ms, log scale) and bytes per point of every structure, grouped
    by point set (a structure is built once per set, so its rows of one set share these values).

Example:
  .venv/bin/python bench/spatial_bench_plot.py bench/results/spatial-2026-11-25.csv
  (writes bench/results/spatial-2026-11-25.png; -o to choose)
"""
import argparse
import csv
import math
import os
import sys


def read_rows(path):
    with open(path, newline='') as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit('%s: no rows' % path)
    for r in rows:
        for k in ('build_ms', 'bytes_per_point', 'queries_per_s', 'results_per_query'):
            r[k] = float(r[k])
    return rows


def unique(values):
    """The distinct values in order of first appearance (the bench's order)."""
    seen = []
    for v in values:
        if v not in seen:
            seen.append(v)
    return seen


def grouped_bars(ax, groups, structures, value, colors, log):
    """Bars of value(group, structure) (None: no bar), one cluster per group."""
    width = 0.8 / max(1, len(structures))
    values = []
    for i, s in enumerate(structures):
        xs, ys = [], []
        for g, group in enumerate(groups):
            v = value(group, s)
            if v is not None and v > 0:
                xs.append(g - 0.4 + (i + 0.5) * width)
                ys.append(v)
        ax.bar(xs, ys, width, label=s, color=colors[s])
        values.extend(ys)
    ax.set_xticks(range(len(groups)))
    ax.set_xticklabels(groups, fontsize=8)
    if log:
        ax.set_yscale('log')
        if values:  # bars from a whole decade below the smallest, so that heights compare
            ax.set_ylim(10 ** math.floor(math.log10(min(values))), max(values) * 1.5)
    ax.grid(axis='y', which='both', alpha=0.3)


def structure_colors(plt, structures):
    """Distinct colours for plain names (grid, hash, kdtree); the variants of one structure's
    option sweep ("multihash(L=512,P=1)", ...) in shades of one sequential colour map."""
    families = unique(s.split('(')[0] for s in structures if '(' in s)
    maps = ['viridis', 'plasma', 'cividis']
    plain = plt.get_cmap('tab10')
    colors = {}
    for s in structures:
        if '(' not in s:
            colors[s] = plain(len(colors) % 10)
    for f, family in enumerate(families):
        members = [s for s in structures if s.split('(')[0] == family and '(' in s]
        cmap = plt.get_cmap(maps[f % len(maps)])
        for i, s in enumerate(members):
            colors[s] = cmap(0.9 * i / max(1, len(members) - 1))
    return colors


def plot(rows, out, title):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

    sets = unique(r['set'] for r in rows)
    structures = unique(r['structure'] for r in rows)
    colors = structure_colors(plt, structures)
    by_key = {(r['set'], r['structure'], r['query']): r for r in rows}
    # Build time and memory: one value per (set, structure).
    built = {(r['set'], r['structure']): r for r in rows}

    cols = max(2, min(4, len(sets)))  # the last row needs two panels
    set_rows = math.ceil(len(sets) / cols)
    fig, axes = plt.subplots(set_rows + 1, cols, figsize=(4.6 * cols, 3.6 * (set_rows + 1)), squeeze=False)
    for i, name in enumerate(sets):
        ax = axes[i // cols][i % cols]
        queries = unique(r['query'] for r in rows if r['set'] == name)
        grouped_bars(ax, queries, structures,
                     lambda q, s: by_key[(name, s, q)]['queries_per_s'] if (name, s, q) in by_key else None,
                     colors, log=True)
        first = next(r for r in rows if r['set'] == name)
        ax.set_title('%s (%s points, %s threads)' % (name, first['points'], first['threads']), fontsize=9)
        ax.set_ylabel('queries/s')
    for i in range(len(sets), set_rows * cols):
        axes[i // cols][i % cols].axis('off')

    bottom = axes[set_rows]
    grouped_bars(bottom[0], sets, structures,
                 lambda g, s: built[(g, s)]['build_ms'] if (g, s) in built else None, colors, log=True)
    bottom[0].set_title('build time', fontsize=9)
    bottom[0].set_ylabel('ms')
    grouped_bars(bottom[1], sets, structures,
                 lambda g, s: built[(g, s)]['bytes_per_point'] if (g, s) in built else None, colors, log=False)
    bottom[1].set_title('memory (structure only, not the points)', fontsize=9)
    bottom[1].set_ylabel('bytes / point')
    for ax in bottom:
        plt.setp(ax.get_xticklabels(), rotation=20, ha='right')
    for ax in bottom[2:]:
        ax.axis('off')

    handles, labels = axes[0][0].get_legend_handles_labels()
    legend_rows = math.ceil(len(structures) / 6)
    top = 1 - (0.025 + 0.02 * legend_rows) * 3 / (set_rows + 1)  # figure fraction of title + legend
    if title:
        fig.suptitle(title, y=0.995, fontsize=10)
    fig.legend(handles, labels, loc='upper center', bbox_to_anchor=(0.5, 1 - 0.03 * 3 / (set_rows + 1)),
               ncol=min(len(structures), 6), fontsize=8)
    fig.tight_layout(rect=(0, 0, 1, top))
    fig.savefig(out, dpi=100)
    print('wrote', out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('csv', help='spatial_bench output')
    ap.add_argument('-o', '--out', help='PNG to write (default: the CSV with .png)')
    ap.add_argument('--title', default='', help='figure title (default: the CSV file name)')
    a = ap.parse_args()
    out = a.out or os.path.splitext(a.csv)[0] + '.png'
    plot(read_rows(a.csv), out, a.title or os.path.basename(a.csv))


if __name__ == '__main__':
    main()
