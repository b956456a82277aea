#!/usr/bin/env python3
"""Metropolis execution modes side by side, in one run: chain-state memory (compact fixed point
against float32), splat accumulation (atomic against sort + gather) and Morton sorting of the
chains (iteration rate with and without), on one scene with a fixed number of mutations.

Each mode is a `caustica render --integrator mlt` with --stats-json; the table and the CSV give
per iteration: trace + advance + splat time, splat time alone, sort time, and bytes per chain.

  bench/mlt_modes.py scenes/cornell-water/scene.xml --res 128x128 --spp 64 --csv out/mlt_modes.csv
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

from csv_out import write_csv

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))

MODES = [
    ('compact, atomic', ['--mlt-state', 'compact', '--splat', 'atomic']),
    ('float, atomic', ['--mlt-state', 'float', '--splat', 'atomic']),
    ('compact, sort', ['--mlt-state', 'compact', '--splat', 'sort']),
    ('compact, atomic, morton/1', ['--mlt-state', 'compact', '--splat', 'atomic', '--mlt-sort-every', '1']),
    ('compact, atomic, morton/8', ['--mlt-state', 'compact', '--splat', 'atomic', '--mlt-sort-every', '8']),
]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('scene')
    ap.add_argument('--res', default='128x128')
    ap.add_argument('--spp', default='64', help='mutations per pixel')
    ap.add_argument('--chains', default='65536')
    ap.add_argument('--max-depth', default='24', help='-D max_depth (the scene must declare it)')
    ap.add_argument('--caustica', default=os.path.join(ROOT, 'build', 'caustica'))
    ap.add_argument('--csv', default='mlt_modes.csv')
    a = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, extra in MODES:
            st_path = os.path.join(tmp, 's.json')
            cmd = [a.caustica, 'render', a.scene, '--integrator', 'mlt', '--res', a.res, '--spp', a.spp,
                   '--mlt-chains', a.chains, '-D', 'max_depth=' + a.max_depth, '-q', '--checkpoint-every', '0',
                   '-o', os.path.join(tmp, 'i.exr'), '--stats-json', st_path] + extra
            p = subprocess.run(cmd, capture_output=True, text=True)
            if p.returncode != 0:
                sys.exit('failed: %s\n%s' % (' '.join(cmd), p.stderr))
            with open(st_path) as f:
                st = json.load(f)
            it = max(1, int(st['mlt_iterations']))
            iter_s = (st['seconds'] - st['mlt_bootstrap_seconds']) / it
            rows.append({'mode': name, 'iterations': it, 'ms_per_iteration': 1e3 * iter_s,
                         'iterations_per_s': 1 / iter_s, 'splat_ms_per_iteration': 1e3 * st['mlt_splat_seconds'] / it,
                         'sort_ms_per_iteration': 1e3 * st['mlt_sort_seconds'] / it,
                         'bytes_per_chain': st['mlt_bytes_per_chain'], 'state_bytes': st['mlt_state_bytes'],
                         'samples_per_s': st['samples_per_second']})
            r = rows[-1]
            print('%-28s %7.1f ms/it  splat %6.2f ms  sort %6.2f ms  %5d B/chain  %.3g Msamples/s' % (
                name, r['ms_per_iteration'], r['splat_ms_per_iteration'], r['sort_ms_per_iteration'],
                r['bytes_per_chain'], r['samples_per_s'] * 1e-6), flush=True)
    write_csv(a.csv, rows)


if __name__ == '__main__':
    main()
