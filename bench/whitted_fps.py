#!/usr/bin/env python3
"""Frames per second of the whitted integrator (issue 21: "Whitted frames per second at 1280x720"),
writing CSV: one row per scene and integrator.

A frame is one sample per pixel at the given resolution. Each scene is rendered with --spp FRAMES
--spp-per-pass 1, so every pass is one frame, and frames/s = FRAMES / the render's seconds (the
stats JSON's `seconds`: rendering only, after the scene is loaded and its BVH built; a preview
renders frame after frame on a loaded scene). The first frame's wall time of a separate
`--spp 1` run, loading and BVH build included, is given beside it, and the CPU seconds the
process used per wall second (below the thread count on a shared machine) and per extra frame
(the difference of the two runs' CPU time over FRAMES - 1). The path tracer at 1 sample
per pixel (its own max_depth) can be measured too for comparison (--integrators whitted,path).

Example:
  bench/whitted_fps.py --csv bench/results/whitted-fps-2026-11-26.csv
  bench/whitted_fps.py --res 1280x720 --frames 8 --integrators whitted,path --threads 2 --csv out/fps.csv

Options the script does not know are passed on to every `caustica render`.
"""
import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time

from csv_out import write_csv

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, '..'))
SCENES = ['cornell-water', 'glass-caustic', 'cornell-box']


def render(a, tmp, scene, integrator, spp):
    stats = os.path.join(tmp, 'stats.json')
    cmd = [a.caustica, 'render', os.path.join(ROOT, 'scenes', scene, 'scene.xml'), '-q',
           '-o', os.path.join(tmp, 'frame.exr'), '--stats-json', stats, '--checkpoint-every', '0',
           '--integrator', integrator, '--res', a.res, '--spp', str(spp), '--spp-per-pass', '1',
           '--seed', '1', '--device', a.device]
    if a.threads:
        cmd += ['--threads', str(a.threads)]
    start, cpu_start = time.perf_counter(), resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(cmd + a.extra, capture_output=True, text=True)
    wall, cpu_end = time.perf_counter() - start, resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (cpu_end.ru_utime + cpu_end.ru_stime) - (cpu_start.ru_utime + cpu_start.ru_stime)
    if p.returncode != 0:
        sys.exit('failed (%d): %s\n%s' % (p.returncode, ' '.join(cmd), p.stderr.strip()))
    with open(stats) as f:
        return json.load(f), wall, cpu


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--caustica', default=os.path.join(ROOT, 'build-cpu', 'caustica'))
    ap.add_argument('--scenes', default=','.join(SCENES), help='bundled scenes (folders of scenes/)')
    ap.add_argument('--integrators', default='whitted', help='comma-separated, e.g. whitted,path')
    ap.add_argument('--res', default='1280x720')
    ap.add_argument('--frames', type=int, default=8, help='frames (1-spp passes) timed per scene')
    ap.add_argument('--threads', type=int, default=0, help='worker threads (default: all cores)')
    ap.add_argument('--device', default='cpu', help='cpu, cuda or auto')
    ap.add_argument('--csv', required=True)
    a, a.extra = ap.parse_known_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in a.scenes.split(','):
            for integrator in a.integrators.split(','):
                first, first_wall, first_cpu = render(a, tmp, scene, integrator, 1)
                st, wall, cpu = render(a, tmp, scene, integrator, a.frames)
                seconds = float(st['seconds'])
                row = {'scene': scene, 'integrator': integrator, 'res': a.res, 'device': a.device,
                       'threads': a.threads or os.cpu_count(), 'frames': a.frames, 'render_seconds': seconds,
                       'frames_per_second': a.frames / seconds, 'ms_per_frame': 1000 * seconds / a.frames,
                       'rays_per_frame': float(st['rays']) / a.frames,
                       'rays_per_second': st['rays_per_second'],
                       'first_frame_wall_seconds': first_wall,
                       # CPU seconds of the process per wall second: below the thread count when
                       # the machine is shared (the frame rate is then pessimistic)
                       'cpu_utilisation': cpu / wall,
                       'frames_cpu_seconds_per_frame': (cpu - first_cpu) / (a.frames - 1) if a.frames > 1 else '',
                       'accel_build_seconds': first['accel_build_seconds']}
                rows.append(row)
                print('%-14s %-8s %s: %.3f frames/s (%.0f ms/frame, %.3g rays/frame), first frame %.2f s wall, '
                      'CPU use %.2f cores' % (scene, integrator, a.res, row['frames_per_second'], row['ms_per_frame'],
                                              row['rays_per_frame'], first_wall, row['cpu_utilisation']), flush=True)
    write_csv(a.csv, rows)


if __name__ == '__main__':
    main()
