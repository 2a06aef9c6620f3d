#!/usr/bin/python3
"""TAA against FXAA, measured against a 4×4 supersampled render of the same frames (the default
scene at 640×360; the reference at 2560×1440 without antialiasing, box-filtered in linear light).

Settings that do not change with the resolution, so that what is measured is aliasing: manual
exposure, no dither, full meshes (RG_LOD=0), the sun's mask at full resolution, SSR off
(ssr_max_roughness = 0), specular anti-aliasing off (it filters by the pixel's size, so 4× the
pixels shade the spheres otherwise — tests/cli/specular_aa.py measures it) and the AO radius at its least (the half-resolution AO and SSR render
differently at 4× the pixels; with them the TAA/FXAA p99 ratio is 0.91, all of it inside the
spheres, not at edges).

  - still: 16 frames, the last compared; TAA's p99 display error must be at most 0.6 × FXAA's;
  - quad swaps: where the device has quad operations in fragment shaders (lavapipe does), TAA
    reads its neighbours inside the pixel's 2×2 quad by a swap (RG_QUAD_OPS); at an odd size
    (helper invocations past the last column and row), still and moving, the images must be
    identical to the fetches' (RG_QUAD_OPS=0);
  - moving (--scene-arg move=1): every frame from 6 on (TAA's history filled) compared with that
    frame's reference: TAA's p99 error must stay below FXAA's (its mean error is printed too: in
    motion TAA softens the surfaces' insides a little, a few % above FXAA's mean); ghosting — the
    error where the reference changed since the frame before by more than 0.1 — is printed.

usage: taa_quality.py RGRAPH SOURCE_ROOT   (prints the figures; exit 1 when a bound fails)
"""

import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

RGRAPH, ROOT = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
SETTINGS = ["--set", "exposure_mode=manual", "--set", "dither=false", "--set", "sun_mask=full",
            "--set", "ssr_max_roughness=0", "--set", "ao_radius=0.05", "--set", "specular_aa=false"]
failures = []


def render(out, size, frames, aa, *extra, env=None):
    p = subprocess.run([RGRAPH, "render", "--size", size, "--frames", frames, "--set",
                        f"antialiasing={aa}", *SETTINGS, *extra, "--out", out], cwd=ROOT,
                       env={**os.environ, "RG_LOD": "0", **(env or {})}, capture_output=True, text=True)
    if p.returncode:
        sys.exit(f"render failed: {p.stderr}")


def display(path):
    return np.asarray(Image.open(path).convert("RGB"), dtype=np.float64) / 255.0


def downsample(path, s=4):
    x = display(path)
    lin = np.where(x <= 0.04045, x / 12.92, ((x + 0.055) / 1.055) ** 2.4)
    h, w, _ = lin.shape
    lin = lin.reshape(h // s, s, w // s, s, 3).mean(axis=(1, 3))
    return np.where(lin <= 0.0031308, lin * 12.92, 1.055 * np.power(lin, 1 / 2.4) - 0.055)


def error(image, reference):
    return np.abs(image - reference).max(axis=2)


def check(name, ok, detail):
    print(("ok   " if ok else "FAIL ") + name + ": " + detail, flush=True)
    if not ok:
        failures.append(name)


def main():
    tmp = tempfile.mkdtemp(prefix="rgraph-taa-")
    try:
        quad(tmp)
        still(tmp)
        moving(tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return 1 if failures else 0


def quad(tmp):
    for name, frames, extra in (("still", "8", []), ("moving", "5", ["--scene-arg", "move=1"])):
        images = []
        for flag in ("0", "1"):
            render(f"{tmp}/quad{flag}.exr", "161x91", frames, "taa", *extra, "--capture", "taa",
                   env={"RG_QUAD_OPS": flag})
            images.append(np.asarray(Image.open(f"{tmp}/quad{flag}.png"), dtype=np.int32))
        differ = int((images[0] != images[1]).any(axis=2).sum())
        # TAA's own output in HDR (the captured `taa` layer), not only the display's 8 bits.
        p = subprocess.run([RGRAPH, "compare", f"{tmp}/quad1.exr", f"{tmp}/quad0.exr", "--layer", "taa"],
                           capture_output=True, text=True)
        rmse = next((line.split()[1] for line in p.stdout.splitlines() if line.strip().startswith("RMSE")), "?")
        check(f"quad swaps, {name}: TAA's image at 161x91 the same as with fetches",
              differ == 0 and p.returncode == 0 and rmse == "0",
              f"{differ} display pixels differ, the HDR's RMSE {rmse}")


def still(tmp):
    render(f"{tmp}/ref.exr", "2560x1440", "4", "none")
    ref = downsample(f"{tmp}/ref.png")
    figures = {}
    for aa in ("taa", "fxaa", "none"):
        render(f"{tmp}/{aa}.exr", "640x360", "16", aa)
        e = error(display(f"{tmp}/{aa}.png"), ref)
        figures[aa] = (e.mean(), np.percentile(e, 99))
        print(f"     still, {aa:4}: mean {e.mean():.4f}, p99 {figures[aa][1]:.4f}")
    ratio = figures["taa"][1] / figures["fxaa"][1]
    check("still: TAA's p99 display error at most 0.6 x FXAA's", ratio <= 0.6,
          f"{figures['taa'][1]:.4f} / {figures['fxaa'][1]:.4f} = {ratio:.2f}")


def moving(tmp):
    move = ["--scene-arg", "move=1"]
    render(f"{tmp}/mref/f.####.exr", "2560x1440", "0..15", "none", *move)
    for aa in ("taa", "fxaa"):
        render(f"{tmp}/m{aa}/f.####.exr", "640x360", "0..15", aa, *move)
    worse, ghost = [], {"taa": [], "fxaa": []}
    previous = None
    for f in range(16):
        ref = downsample(f"{tmp}/mref/f.{f:04d}.png")
        errs = {aa: error(display(f"{tmp}/m{aa}/f.{f:04d}.png"), ref) for aa in ("taa", "fxaa")}
        if previous is not None:
            changed = np.abs(ref - previous).max(axis=2) > 0.1
            for aa in errs:
                ghost[aa].append(errs[aa][changed].mean() if changed.any() else 0.0)
        previous = ref
        if f >= 6:
            t, x = errs["taa"].mean(), errs["fxaa"].mean()
            print(f"     moving, frame {f:2}: mean error TAA {t:.4f}, FXAA {x:.4f}; p99 TAA "
                  f"{np.percentile(errs['taa'], 99):.4f}, FXAA {np.percentile(errs['fxaa'], 99):.4f}")
            if np.percentile(errs["taa"], 99) >= np.percentile(errs["fxaa"], 99):
                worse.append(f)
    print(f"     moving, ghosting (mean error where the reference changed by > 0.1 since the frame "
          f"before): TAA {np.mean(ghost['taa']):.4f}, FXAA {np.mean(ghost['fxaa']):.4f}")
    check("moving: every frame's TAA p99 error below FXAA's", not worse, f"frames {worse}" if worse else "frames 6..15")


if __name__ == "__main__":
    sys.exit(main())
