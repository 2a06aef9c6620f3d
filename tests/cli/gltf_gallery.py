#!/usr/bin/python3
"""The glTF conformance models (tools/gltf_models.py) through `rgraph gallery`: every model has
the status it should (rendered; rendered with the loader's warnings; refused with its reason), the
page lists each with its image and what the loader said, and each rendered model matches its
golden image (tests/golden/images/gltf_gallery/NAME.exr, blessed from renders that were looked
at): a feature the loader dropped (a skin, a morph target, a texture's TEXCOORD_n, a material
extension) changes its image. Goldens are lavapipe's; on another device the images are checked
to exist only.

usage: gltf_gallery.py RGRAPH SOURCE_ROOT [--update]   (exit 1 when a check fails)
"""

import html as markup
import os
import re
import shutil
import subprocess
import sys
import tempfile

RGRAPH, ROOT = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
UPDATE = "--update" in sys.argv
GOLDEN = os.path.join(ROOT, "tests", "golden", "images", "gltf_gallery")
PYTHON = sys.executable  # Debian's, with python3-numpy

EXPECTED = {
    "broken_index.gltf": ("refused", "mesh 0 primitive 0: material 7 does not exist"),
    "broken_schema.gltf": ("refused", "nodes[0].scale: expected an array of 3 numbers"),
    "broken_required.gltf": ("refused", "requires extension 'KHR_not_an_extension'"),
    "ior_specular.gltf": ("warnings", "is above the 16 % reflectance can hold"),
}

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def main():
    tmp = tempfile.mkdtemp(prefix="rgraph_gallery_")
    try:
        models = os.path.join(tmp, "models")
        subprocess.run([PYTHON, os.path.join(ROOT, "tools", "gltf_models.py"), models], check=True)
        names = sorted(f for f in os.listdir(models) if f.endswith(".gltf"))
        page = os.path.join(tmp, "page", "index.html")
        run = subprocess.run([RGRAPH, "gallery", models, "--out", page, "--size", "128x96",
                              "--frames", "4"], capture_output=True, text=True)
        sys.stderr.write(run.stderr)
        check(run.returncode == 0, f"rgraph gallery exits 0 (got {run.returncode})")
        status = dict(re.findall(r"rgraph: gallery \[\d+/\d+\] (\S+): (\w[\w ]*) \(", run.stderr))
        check(sorted(status) == names, f"every model reported ({len(status)} of {len(names)})")
        html = open(page).read() if os.path.exists(page) else ""
        files = os.path.join(tmp, "page", "index_files")
        for name in names:
            want, said = EXPECTED.get(name, ("ok", None))
            check(status.get(name) == want, f"{name}: {want} (got {status.get(name)})")
            check(f'<div class="name">{name}</div>' in html, f"{name}: on the page")
            if said:
                check(said in markup.unescape(html), f"{name}: the page says '{said}'")
            if want == "refused":
                continue
            exr = os.path.join(files, name + ".exr")
            check(f'src="index_files/{name}.png"' in html and os.path.exists(exr[:-4] + ".png"),
                  f"{name}: its image on the page")
            log = open(os.path.join(files, name + ".log")).read()
            golden = os.path.join(GOLDEN, name[:-5] + ".exr")
            if UPDATE:
                os.makedirs(GOLDEN, exist_ok=True)
                shutil.copy(exr, golden)
                shutil.copy(exr[:-4] + ".png", golden[:-4] + ".png")
                print(f"updated {golden}")
                continue
            if "llvmpipe" not in log:
                print(f"skip {name}: golden images are lavapipe's")
                continue
            if not os.path.exists(golden):
                check(False, f"{name}: golden {os.path.relpath(golden, ROOT)} exists (--update)")
                continue
            # The golden suite's HDR bound across host CPUs, with room (tests/examples/package.sh).
            cmp = subprocess.run([RGRAPH, "compare", exr, golden, "--tolerance", "1e-4"],
                                 capture_output=True, text=True)
            check(cmp.returncode == 0, f"{name}: matches its golden ({cmp.stdout.strip()})")
        # Chromium can open the page: it names every model (checked above) and is one file.
        check(html.count('<div class="card">') == len(names), "one card per model")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
