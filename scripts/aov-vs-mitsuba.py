#!/usr/bin/env python3
"""Compares caustica's AOVs with Mitsuba 3's aov integrator on a bundled scene.

    scripts/aov-vs-mitsuba.py CAUSTICA_BINARY SCENE.xml [--res 64] [--spp 16]

Wraps the scene's <integrator> in Mitsuba's aov integrator (depth, sh_normal, geo_normal, albedo,
position, uv), renders it with Mitsuba (scalar_rgb) and with `caustica render --aov` at the same
size and sample count, and prints per AOV the mean absolute difference over all pixels and over
the pixels whose 3x3 neighbourhood lies on one surface in both (edges are covered by different
random samples in the two renderers)."""
import argparse, os, re, subprocess, sys, tempfile
import numpy as np
import mitsuba as mi

AOVS = "dd.y:depth,nn:sh_normal,ng:geo_normal,pos:position,uv:uv,alb:albedo"

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("caustica"); ap.add_argument("scene")
    ap.add_argument("--res", type=int, default=64); ap.add_argument("--spp", type=int, default=16)
    a = ap.parse_args()
    mi.set_variant("scalar_rgb")
    text = open(a.scene).read()
    wrapped = re.sub(r"(<integrator\b[^>]*>.*?</integrator>)",
                     lambda m: '<integrator type="aov"><string name="aovs" value="%s"/>%s</integrator>'
                     % (AOVS, m.group(1)), text, count=1, flags=re.S)
    with tempfile.TemporaryDirectory(dir=os.path.dirname(os.path.abspath(a.scene))) as tmp:
        xml = os.path.join(tmp, "aov.xml")
        open(xml, "w").write(wrapped.replace('="meshes/', '="../meshes/'))
        scene = mi.load_file(xml, width=a.res, height=a.res, spp=a.spp)
        img = mi.render(scene, spp=a.spp)
        bmp = scene.sensors()[0].film().bitmap()
        mits = {n: np.array(l) for n, l in bmp.split()}
        out = os.path.join(tmp, "c.exr")
        subprocess.run([a.caustica, "render", a.scene, "--res", "%dx%d" % (a.res, a.res), "--spp", str(a.spp),
                        "--aov", AOVS, "-o", out, "-q"], check=True)
        caus = {n: np.array(l) for n, l in mi.Bitmap(out).split()}
    depth_m, depth_c = mits["dd.y"], caus["dd.y"]
    d = np.squeeze(depth_m)
    # Interior: depth smooth in a 3x3 window in Mitsuba's image (no silhouette).
    from numpy.lib.stride_tricks import sliding_window_view as win
    w = win(np.pad(d, 1, mode="edge"), (3, 3))
    interior = (w.max(axis=(2, 3)) - w.min(axis=(2, 3))) < 0.05 * np.maximum(d, 1e-3)
    print("pixels %d, interior %d" % (d.size, interior.sum()))
    for name in ["dd.y", "nn", "ng", "pos", "uv", "alb"]:
        m, c = mits[name].reshape(a.res, a.res, -1), caus[name].reshape(a.res, a.res, -1)
        diff = np.abs(m - c).max(axis=2)
        print("%-5s mean |diff| all %.4g, interior %.4g, interior max %.4g (value range %.3g..%.3g)"
              % (name, diff.mean(), diff[interior].mean(), diff[interior].max(), m.min(), m.max()))

if __name__ == "__main__":
    main()
