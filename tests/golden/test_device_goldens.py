#!/usr/bin/python3
"""Goldens per device family (graph/golden/golden_set.h), on lavapipe: a second family is simulated
with RG_DEVICE_FAMILY (and LP_NUM_THREADS=1 for its goldens), its "recorded foreign goldens" made
by blessing under it and then altering them. On a copy of two tests' goldens:

  - a family without goldens of its own passes by the test's cross-device bound alone (or, for a
    test that states none, by the test's comparisons against the primary goldens);
  - --update under it writes images/NAME/devices/FAMILY/ with its own golden.json and leaves the
    primary goldens byte for byte as they were;
  - a family's own goldens are what it compares with: altered, its run fails and the primary's not;
  - the cross-device bound holds every family to the primary goldens even when its own pass;
  - JUnit names the family.

usage: test_device_goldens.py RGRAPH SOURCE_ROOT
"""

import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

from PIL import Image

RGRAPH, ROOT = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
failures = []


def check(name, ok, detail=""):
    print(("ok   " if ok else "FAIL ") + name, flush=True)
    if not ok:
        print("\n".join(detail.splitlines()[-25:]))
        failures.append(name)


def test(images, pattern, family=None, *extra, threads=None):
    env = {k: v for k, v in os.environ.items() if k != "RG_DEVICE_FAMILY"}
    if family:
        env["RG_DEVICE_FAMILY"] = family
    if threads:
        env["LP_NUM_THREADS"] = threads
    p = subprocess.run([RGRAPH, "test", pattern, "--images", images, "--out",
                        os.path.join(os.path.dirname(images), "out"), *extra],
                       cwd=ROOT, env=env, capture_output=True, text=True)
    return p.returncode, p.stdout + p.stderr


def digest(folder):
    h = hashlib.sha256()
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        if os.path.isfile(path):
            h.update(name.encode())
            h.update(open(path, "rb").read())
    return h.hexdigest()


def scale_png(path, factor, offset=0):
    img = Image.open(path)
    img.point(lambda v: min(255, int(v * factor + offset))).save(path)


def main():
    family = subprocess.run([RGRAPH, "devices", "--family"], capture_output=True, text=True).stdout.strip()
    if family != "llvmpipe":  # the goldens here are lavapipe's: this device would be the second family
        print(f"skipped: the primary goldens are llvmpipe's and this device's family is '{family}'")
        return 77
    tmp = tempfile.mkdtemp(prefix="rgraph-device-goldens-")
    try:
        images = os.path.join(tmp, "images")
        for name in ("shading", "gbuffer_layout"):
            shutil.copytree(os.path.join(ROOT, "tests", "golden", "images", name),
                            os.path.join(images, name))
        shading = os.path.join(images, "shading")
        second = os.path.join(shading, "devices", "second")
        primary = digest(shading)

        rc, out = test(images, "shading")
        check("the primary family passes with its goldens", rc == 0 and "family llvmpipe" in out, out)

        rc, out = test(images, "shading", "second")
        check("a family without goldens passes by the cross-device bound",
              rc == 0 and "not compared: no goldens of device family 'second'" in out and
              "ldr@llvmpipe" in out and "flip" in out, out)
        rc, out = test(images, "gbuffer_layout", "second")
        check("a test without a cross-device bound compares with the primary goldens",
              rc == 0 and "@llvmpipe" not in out and "not compared" not in out, out)

        rc, out = test(images, "shading", "second", "--update", threads="1")
        check("--update blesses the running family's goldens", rc == 0 and os.path.isdir(second), out)
        sidecar = json.load(open(os.path.join(second, "golden.json"))) if os.path.isdir(second) else {}
        made = sidecar.get("made_with", {})
        check("its golden.json records the family and profile",
              made.get("family") == "second" and made.get("lp_num_threads") == "1", json.dumps(made))
        check("the primary goldens are untouched", digest(shading) == primary)
        check("the family's set holds every capture",
              all(os.path.isfile(os.path.join(second, f)) for f in
                  ("ldr.png", "albedo.png", "hdr.exr", "normal.exr", "material.exr")),
              str(os.listdir(second) if os.path.isdir(second) else []))

        rc, out = test(images, "shading", "second")
        check("the family compares with its own goldens, and the cross-device bound",
              rc == 0 and "not compared" not in out and "ldr@llvmpipe" in out, out)

        # A recorded foreign golden that differs: the family's own display golden 3 steps brighter.
        keep = open(os.path.join(second, "ldr.png"), "rb").read()
        scale_png(os.path.join(second, "ldr.png"), 1.0, 3)
        rc, out = test(images, "shading", "second")
        check("an altered family golden fails that family's run",
              rc == 1 and "first divergent resource in pipeline order: 'ldr'" in out, out)
        rc, out = test(images, "shading")
        check("and not the primary family's", rc == 0, out)
        open(os.path.join(second, "ldr.png"), "wb").write(keep)

        # The primary display golden far off: the family's own goldens pass, the bound does not.
        scale_png(os.path.join(shading, "ldr.png"), 1.6)
        rc, out = test(images, "shading", "second", "--junit", os.path.join(tmp, "j.xml"))
        check("the cross-device bound fails a family that drifts from the primary goldens",
              rc == 1 and "first divergent resource in pipeline order: 'ldr@llvmpipe'" in out, out)
        props = {p.get("name"): p.get("value")
                 for p in ET.parse(os.path.join(tmp, "j.xml")).getroot().iter("property")}
        check("JUnit names the device family", props.get("device_family") == "second", str(props))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
