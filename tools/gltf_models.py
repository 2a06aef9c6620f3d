#!/usr/bin/env python3
"""Writes small glTF models, one per feature rgraph's loader reads, in the spirit of the Khronos
glTF-Asset-Generator: each a self-contained .gltf (buffers and images as data URIs) that shows
its feature at a glance, plus a few deliberately broken files the loader must refuse.

Usage: tools/gltf_models.py OUT_DIR [--list]
       tools/gltf_models.py OUT_DIR --many N   (many_meshes_N.gltf and .bin: N nodes, each with a
                                                mesh of its own — the loader's speed)

`rgraph gallery OUT_DIR --out OUT_DIR/index.html` renders them all into one page. Needs
python3-numpy (Debian)."""
import base64
import json
import math
import os
import struct
import sys
import zlib

import numpy as np

FLOAT, UBYTE, USHORT, UINT, BYTE, SHORT = 5126, 5121, 5123, 5125, 5120, 5122
TYPES = {1: "SCALAR", 2: "VEC2", 3: "VEC3", 4: "VEC4", 16: "MAT4"}


def png(width, height, rgba):
    """RGBA8 pixels (height x width x 4 uint8) as PNG bytes."""
    raw = b"".join(b"\0" + rgba[y].tobytes() for y in range(height))
    chunk = lambda kind, data: (struct.pack(">I", len(data)) + kind + data +
                                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def checker(n=64, cells=8, a=(230, 230, 230), b=(40, 40, 40)):
    y, x = np.mgrid[0:n, 0:n]
    on = ((x * cells // n + y * cells // n) % 2).astype(bool)
    img = np.zeros((n, n, 4), np.uint8)
    img[..., 3] = 255
    img[on, :3] = a
    img[~on, :3] = b
    return img


def label(n=64):
    """A bright 'E' on black: an emissive label."""
    img = np.zeros((n, n, 4), np.uint8)
    img[..., 3] = 255
    s = n // 8
    img[s:n - s, 2 * s:3 * s, :3] = 255
    for row in (s, n // 2 - s // 2, n - 2 * s):
        img[row:row + s, 2 * s:6 * s, :3] = 255
    return img


class Doc:
    def __init__(self):
        self.j = {"asset": {"version": "2.0", "generator": "rgraph tools/gltf_models.py"},
                  "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [],
                  "accessors": [], "bufferViews": [], "materials": []}
        self.bin = bytearray()

    def view(self, data, stride=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        v = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if stride:
            v["byteStride"] = stride
        self.bin += data
        self.j["bufferViews"].append(v)
        return len(self.j["bufferViews"]) - 1

    def accessor(self, array, component=FLOAT, normalized=False, bounds=False):
        a = np.ascontiguousarray(array)
        comps = 1 if a.ndim == 1 else a.shape[1]
        dtype = {FLOAT: np.float32, UBYTE: np.uint8, USHORT: np.uint16, UINT: np.uint32,
                 BYTE: np.int8, SHORT: np.int16}[component]
        data = a.astype(dtype)
        acc = {"bufferView": self.view(data.tobytes()), "componentType": component,
               "count": int(a.shape[0]), "type": TYPES[comps]}
        if normalized:
            acc["normalized"] = True
        if bounds:
            flat = data.reshape(len(data), -1)
            acc["min"] = [float(v) for v in flat.min(axis=0)]
            acc["max"] = [float(v) for v in flat.max(axis=0)]
        self.j["accessors"].append(acc)
        return len(self.j["accessors"]) - 1

    def material(self, m):
        self.j["materials"].append(m)
        return len(self.j["materials"]) - 1

    def image(self, pixels):
        uri = "data:image/png;base64," + base64.b64encode(png(pixels.shape[1], pixels.shape[0], pixels)).decode()
        self.j.setdefault("images", []).append({"uri": uri})
        self.j.setdefault("textures", []).append({"source": len(self.j["images"]) - 1})
        return len(self.j["textures"]) - 1

    def prim(self, geom, material=None, extra_attrs=None, mode=None):
        pos, nrm, uv, idx = geom
        attrs = {"POSITION": self.accessor(pos, bounds=True), "NORMAL": self.accessor(nrm)}
        if uv is not None:
            attrs["TEXCOORD_0"] = self.accessor(uv)
        attrs.update(extra_attrs or {})
        p = {"attributes": attrs}
        if idx is not None:
            p["indices"] = self.accessor(idx, UINT if len(pos) > 65535 else USHORT)
        if material is not None:
            p["material"] = material
        if mode is not None:
            p["mode"] = mode
        return p

    def mesh(self, prims, **extra):
        self.j["meshes"].append(dict({"primitives": prims}, **extra))
        return len(self.j["meshes"]) - 1

    def node(self, root=True, **n):
        self.j["nodes"].append(n)
        i = len(self.j["nodes"]) - 1
        if root:
            self.j["scenes"][0]["nodes"].append(i)
        return i

    def uses(self, *ext, required=False):
        for e in ext:
            self.j.setdefault("extensionsUsed", []).append(e)
            if required:
                self.j.setdefault("extensionsRequired", []).append(e)

    def write(self, path, external=False):
        # The buffer inside the file as a data URI, or (external) in a .bin beside it.
        if self.bin and external:
            name = os.path.splitext(os.path.basename(path))[0] + ".bin"
            with open(os.path.join(os.path.dirname(path), name), "wb") as f:
                f.write(bytes(self.bin))
            self.j["buffers"] = [{"byteLength": len(self.bin), "uri": name}]
        elif self.bin:
            self.j["buffers"] = [{"byteLength": len(self.bin), "uri": "data:application/octet-stream;base64," +
                                  base64.b64encode(bytes(self.bin)).decode()}]
        for k in [k for k, v in self.j.items() if v == []]:
            del self.j[k]
        with open(path, "w") as f:
            json.dump(self.j, f, indent=1)


# ---- geometry: (positions, normals, uvs, indices) -------------------------------------------

def grid(nx, ny, fn):
    """A parametric surface: fn(u, v) -> point, over (nx+1) x (ny+1) vertices; normals from the
    surface's derivatives (d/du x d/dv), the triangles counter-clockwise seen from their side."""
    u, v = np.meshgrid(np.linspace(0, 1, nx + 1), np.linspace(0, 1, ny + 1))
    p = fn(u, v)
    du = np.gradient(p, axis=1)
    dv = np.gradient(p, axis=0)
    n = np.cross(du, dv)
    n /= np.maximum(np.linalg.norm(n, axis=-1, keepdims=True), 1e-12)
    idx = []
    for y in range(ny):
        for x in range(nx):
            a = y * (nx + 1) + x
            idx += [a, a + 1, a + nx + 2, a, a + nx + 2, a + nx + 1]
    uv = np.stack([u, 1 - v], -1).reshape(-1, 2)  # v up the surface, glTF's v down the image
    return p.reshape(-1, 3), n.reshape(-1, 3), uv, np.array(idx)


def sphere(r=0.5, seg=32):
    pos, nrm, uv, idx = grid(seg, seg // 2, lambda u, v: np.stack(
        [r * np.sin(v * math.pi) * np.cos(u * 2 * math.pi), r * np.cos(v * math.pi),
         -r * np.sin(v * math.pi) * np.sin(u * 2 * math.pi)], -1))
    # The exact normals (the derivatives vanish at the poles); the triangles turned to face out.
    return pos, pos / r, uv, idx.reshape(-1, 3)[:, ::-1].reshape(-1)


def quad(w=1.0, h=1.0):
    return grid(1, 1, lambda u, v: np.stack([(u - 0.5) * w, (v - 0.5) * h, 0 * u], -1))


def tube(r=0.15, length=1.6, rings=16, seg=16):
    """A capped-less tube along +y from 0 to `length` (skins and morphs bend it)."""
    return grid(seg, rings, lambda u, v: np.stack(
        [r * np.cos(u * 2 * math.pi), length * v, -r * np.sin(u * 2 * math.pi)], -1))


def look_at(eye, target):
    """The rotation (x, y, z, w) turning glTF's camera (looking down -z, +y up) towards target."""
    f = (target - eye) / np.linalg.norm(target - eye)
    r = np.cross(f, [0, 1, 0])
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    m = np.stack([r, u, -f], 1)  # columns: the camera's x, y, z in the world
    w = math.sqrt(max(1 + m[0, 0] + m[1, 1] + m[2, 2], 1e-12)) / 2
    return [(m[2, 1] - m[1, 2]) / (4 * w), (m[0, 2] - m[2, 0]) / (4 * w), (m[1, 0] - m[0, 1]) / (4 * w), w]


def pbr(color, metallic=0.0, roughness=0.5, **extra):
    m = {"pbrMetallicRoughness": {"baseColorFactor": list(color) + [1.0] if len(color) == 3 else list(color),
                                  "metallicFactor": metallic, "roughnessFactor": roughness}}
    m.update(extra)
    return m


# ---- the models -----------------------------------------------------------------------------

def basic(d):
    d.node(mesh=d.mesh([d.prim(sphere(), d.material(pbr((0.8, 0.2, 0.1))))]))


def metal_rough_spheres(d):
    for i in range(5):
        for k, metal in enumerate((0.0, 1.0)):
            m = d.material(pbr((0.9, 0.6, 0.2), metal, 0.05 + 0.9 * i / 4))
            d.node(mesh=d.mesh([d.prim(sphere(0.2), m)]), translation=[(i - 2) * 0.5, (k - 0.5) * 0.5, 0])


def primitive_modes(d):
    # A square as a TRIANGLE_STRIP and as a TRIANGLE_FAN.
    pos = np.array([[0, 0, 0], [0.8, 0, 0], [0, 0.8, 0], [0.8, 0.8, 0]], float)
    nrm = np.tile([0, 0, 1.0], (4, 1))
    m = d.material(pbr((0.2, 0.6, 0.9)))
    strip = d.prim((pos, nrm, None, np.array([0, 1, 2, 3])), m, mode=5)
    fan = d.prim((pos, nrm, None, np.array([0, 1, 3, 2])), m, mode=6)
    d.node(mesh=d.mesh([strip]), translation=[-1, 0, 0])
    d.node(mesh=d.mesh([fan]), translation=[0.2, 0, 0])


def lines_and_points(d):
    # Every mode that is not triangles, beside a triangle: LINES (its outline), a LINE_STRIP
    # (a zigzag), a LINE_LOOP with COLOR_0 (red, green, blue, white corners), POINTS (a 9×9 grid)
    # — drawn unlit in the material's base colour, one pixel wide.
    pos = np.array([[0, 0, 0], [1, 0, 0], [0.5, 0.8, 0]], float)
    nrm = np.tile([0, 0, 1.0], (3, 1))
    m = d.material(pbr((0.9, 0.9, 0.2)))
    zig = np.array([[0.25 * i, 0.8 * (i % 2), 0] for i in range(5)], float)
    square = np.array([[0, 0, 0], [0.8, 0, 0], [0.8, 0.8, 0], [0, 0.8, 0]], float)
    corners = np.array([[255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [255, 255, 255, 255]])
    grid = np.array([[0.1 * x, 0.1 * y, 0] for y in range(9) for x in range(9)], float)
    white = d.material(pbr((1, 1, 1)))
    d.node(mesh=d.mesh([d.prim((pos - [2.4, 0, 0], nrm, None, None), m),
                        d.prim((pos - [1.2, 0, 0], nrm, None, np.array([0, 1, 1, 2, 2, 0])), m, mode=1),
                        d.prim((zig, np.tile([0, 0, 1.0], (5, 1)), None, None), m, mode=3),
                        d.prim((square + [1.2, 0, 0], np.tile([0, 0, 1.0], (4, 1)), None, None), white,
                               {"COLOR_0": d.accessor(corners, UBYTE, normalized=True)}, mode=2),
                        d.prim((grid + [2.2, 0, 0], np.tile([0, 0, 1.0], (81, 1)), None, None), m, mode=0)]))


def vertex_colors(d):
    # COLOR_0 times the base colour: a white sphere coloured by its normal (float RGB), and a
    # quad with red, green, blue and white corners (normalised unsigned bytes, RGBA).
    pos, nrm, uv, idx = sphere(0.45)
    white = d.material(pbr((1, 1, 1)))
    d.node(mesh=d.mesh([d.prim((pos, nrm, uv, idx), white, {"COLOR_0": d.accessor(nrm * 0.5 + 0.5)})]),
           translation=[-0.55, 0, 0])
    corners = np.array([[255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [255, 255, 255, 255]])
    d.node(mesh=d.mesh([d.prim(quad(0.9, 0.9), white,
                               {"COLOR_0": d.accessor(corners, UBYTE, normalized=True)})]),
           translation=[0.55, 0, 0])


def texture_transform(d):
    t = d.image(checker())
    for i, (offset, rot, scale) in enumerate([((0, 0), 0, (1, 1)), ((0.25, 0), 0.4, (2, 2)),
                                              ((0, 0.5), 0, (4, 1))]):
        ref = {"index": t}
        if i:
            ref["extensions"] = {"KHR_texture_transform": {"offset": list(offset), "rotation": rot,
                                                           "scale": list(scale)}}
        m = d.material(pbr((1, 1, 1)))
        d.j["materials"][m]["pbrMetallicRoughness"]["baseColorTexture"] = ref
        d.node(mesh=d.mesh([d.prim(quad(), m)]), translation=[(i - 1) * 1.1, 0, 0])
    d.uses("KHR_texture_transform")


def texcoord_sets(d):
    # The checker on TEXCOORD_2 (four times as dense as TEXCOORD_0, which would show one cell).
    t = d.image(checker())
    g = quad()
    m = d.material(pbr((1, 1, 1)))
    d.j["materials"][m]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": t, "texCoord": 2}
    extra = {"TEXCOORD_1": d.accessor(g[2] * 0.1), "TEXCOORD_2": d.accessor(g[2] * 4.0)}
    d.node(mesh=d.mesh([d.prim((g[0], g[1], g[2] * 0.125, g[3]), m, extra)]))


def quantized(d):
    # KHR_mesh_quantization: positions as normalised shorts, normals as normalised bytes, the
    # node's scale undoing the quantisation.
    pos, nrm, uv, idx = sphere(0.5, 24)
    p = d.accessor(np.round(pos / 0.5 * 32767), SHORT, normalized=True, bounds=True)
    n = d.accessor(np.round(nrm * 127), BYTE, normalized=True)
    prim = {"attributes": {"POSITION": p, "NORMAL": n}, "indices": d.accessor(idx, USHORT),
            "material": d.material(pbr((0.3, 0.8, 0.3)))}
    d.node(mesh=d.mesh([prim]), scale=[0.5, 0.5, 0.5])
    d.uses("KHR_mesh_quantization", required=True)


def morph_targets(d):
    # A tube bulged by target 0 (weight 1) and bent sideways by target 1 (weight 0.5).
    pos, nrm, uv, idx = tube()
    y = pos[:, 1:2]
    bulge = np.concatenate([pos[:, :1], 0 * y, pos[:, 2:]], 1) * np.sin(y / 1.6 * math.pi) * 1.5
    bend = np.concatenate([(y / 1.6) ** 2 * 0.8, 0 * y, 0 * y], 1)
    prim = d.prim((pos, nrm, uv, idx), d.material(pbr((0.7, 0.3, 0.8))))
    prim["targets"] = [{"POSITION": d.accessor(bulge)}, {"POSITION": d.accessor(bend)}]
    d.node(mesh=d.mesh([prim], weights=[1.0, 0.5]), translation=[0, -0.8, 0])


def skin(d):
    # A tube on two joints: the upper joint turned 60° about z, vertices blended over its middle.
    pos, nrm, uv, idx = tube()
    w1 = np.clip((pos[:, 1] - 0.6) / 0.4, 0, 1)
    joints = np.zeros((len(pos), 4))
    joints[:, 1] = 1
    weights = np.stack([1 - w1, w1, 0 * w1, 0 * w1], 1)
    prim = d.prim((pos, nrm, uv, idx), d.material(pbr((0.9, 0.8, 0.6))),
                  {"JOINTS_0": d.accessor(joints, UBYTE), "WEIGHTS_0": d.accessor(weights)})
    ibm = np.stack([np.eye(4), np.eye(4)]).astype(np.float32)
    ibm[1][3, 1] = -0.8  # column-major: joint 1's bind pose is at y = 0.8
    q = [0, 0, math.sin(math.radians(30)), math.cos(math.radians(30))]
    upper = d.node(root=False, name="upper", translation=[0, 0.8, 0], rotation=q)
    lower = d.node(name="lower", children=[upper], translation=[0, -0.8, 0])
    d.j.setdefault("skins", []).append({"joints": [lower, upper],
                                        "inverseBindMatrices": d.accessor(ibm.reshape(2, 16))})
    d.node(name="body", mesh=d.mesh([prim]), skin=0)


def instancing(d):
    n = 5
    t = np.array([[x - 2, y - 2, 0] for y in range(n) for x in range(n)], float) * 0.45
    s = np.tile([0.15, 0.15, 0.15], (n * n, 1)) * (1 + np.arange(n * n)[:, None] % 3 * 0.3)
    mesh = d.mesh([d.prim(sphere(), d.material(pbr((0.2, 0.4, 0.9), 0.0, 0.3)))])
    d.node(mesh=mesh, extensions={"EXT_mesh_gpu_instancing": {"attributes": {
        "TRANSLATION": d.accessor(t), "SCALE": d.accessor(s)}}})
    d.uses("EXT_mesh_gpu_instancing", required=True)


def variants(d):
    red, blue = d.material(pbr((0.9, 0.1, 0.1))), d.material(pbr((0.1, 0.2, 0.9)))
    prim = d.prim(sphere(), red)
    prim["extensions"] = {"KHR_materials_variants": {"mappings": [{"material": blue, "variants": [1]}]}}
    d.node(mesh=d.mesh([prim]))
    d.j["extensions"] = {"KHR_materials_variants": {"variants": [{"name": "red"}, {"name": "blue"}]}}
    d.uses("KHR_materials_variants")


def unlit(d):
    m = d.material(pbr((0.1, 0.7, 0.3), extensions={"KHR_materials_unlit": {}}))
    d.node(mesh=d.mesh([d.prim(sphere(), m)]))
    d.uses("KHR_materials_unlit")


def emissive_label(d):
    # A label as emissive texture on a black base, then the same at emissive strength 4.
    t = d.image(label())
    for i, strength in enumerate((1.0, 4.0)):
        m = pbr((0, 0, 0), 0, 1, emissiveTexture={"index": t}, emissiveFactor=[1, 0.8, 0.3])
        if strength != 1:
            m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
        d.node(mesh=d.mesh([d.prim(quad(), d.material(m))]), translation=[(i - 0.5) * 1.1, 0, 0])
    d.uses("KHR_materials_emissive_strength")


def ripples(n=64, waves=6, depth=0.6):
    """A tangent-space normal map of ridges across u (RGB, +Y up as glTF's)."""
    u = (np.arange(n) + 0.5) / n
    slope = depth * np.cos(u * waves * 2 * math.pi)
    nrm = np.stack([-slope, np.zeros(n), np.ones(n)], -1)
    nrm /= np.linalg.norm(nrm, axis=-1, keepdims=True)
    img = np.zeros((n, n, 4), np.uint8)
    img[..., :3] = np.round((nrm[None, :, :] * 0.5 + 0.5) * 255).astype(np.uint8)
    img[..., 3] = 255
    return img


def clearcoat(d):
    # No coat, a smooth coat, and a coat in bands: clearcoatTexture's R (coat or none) across
    # clearcoatRoughnessTexture's G (smooth or rough) in cells. Then a rippled base (normalTexture)
    # under a smooth coat — its reflections stay smooth, the coat takes the vertex normal — and the
    # same with the ripples as clearcoatNormalTexture too: the coat's reflections ripple.
    bands = checker(64, 4, (255, 255, 255), (0, 0, 0))
    rough = checker(64, 8, (0, 200, 0), (0, 20, 0))
    bumps = d.image(ripples())
    for i, coat in enumerate((0.0, 1.0, 1.0, 1.0, 1.0)):
        m = pbr((0.6, 0.05, 0.05), 0, 0.6)
        if coat:
            x = {"clearcoatFactor": coat, "clearcoatRoughnessFactor": 0.5 if i == 2 else 0.05}
            if i == 2:
                x["clearcoatTexture"] = {"index": d.image(bands)}
                x["clearcoatRoughnessTexture"] = {"index": d.image(rough)}
            if i >= 3:
                m["normalTexture"] = {"index": bumps}
            if i == 4:
                x["clearcoatNormalTexture"] = {"index": bumps, "scale": 1.0}
            m["extensions"] = {"KHR_materials_clearcoat": x}
        d.node(mesh=d.mesh([d.prim(sphere(0.3), d.material(m))]), translation=[(i - 2) * 0.7, 0, 0])
    d.uses("KHR_materials_clearcoat")


def ior_specular(d):
    for i, (ior, spec) in enumerate(((1.0, 1.0), (1.5, 1.0), (2.5, 1.0), (1.5, 0.0))):
        m = pbr((0.05, 0.05, 0.05), 0, 0.2, extensions={
            "KHR_materials_ior": {"ior": ior}, "KHR_materials_specular": {"specularFactor": spec}})
        d.node(mesh=d.mesh([d.prim(sphere(0.22), d.material(m))]), translation=[(i - 1.5) * 0.55, 0, 0])
    d.uses("KHR_materials_ior", "KHR_materials_specular")


def specular_glossiness(d):
    # Three glossiness factors, then specularGlossinessTexture in cells: gold and glossy, or dark
    # and rough (RGB sRGB × specularFactor, A × glossinessFactor).
    cells = checker(64, 4, (255, 200, 80), (30, 30, 30))
    cells[..., 3] = np.where(cells[..., 0] > 128, 240, 60)
    for i, gloss in enumerate((0.2, 0.6, 0.95, 1.0)):
        x = {"diffuseFactor": [0.1, 0.3, 0.6, 1], "specularFactor": [0.5, 0.5, 0.5],
             "glossinessFactor": gloss}
        if i == 3:
            x["specularFactor"] = [1, 1, 1]
            x["diffuseFactor"] = [0.02, 0.02, 0.02, 1]
            x["specularGlossinessTexture"] = {"index": d.image(cells)}
        m = {"extensions": {"KHR_materials_pbrSpecularGlossiness": x}}
        d.node(mesh=d.mesh([d.prim(sphere(0.25), d.material(m))]), translation=[(i - 1.5) * 0.6, 0, 0])
    d.uses("KHR_materials_pbrSpecularGlossiness")


def sheen(d):
    # A dark red cloth without sheen, then a white sheen smooth and rough, a coloured one, and one
    # whose colour comes from sheenColorTexture (stripes, sRGB) and roughness from
    # sheenRoughnessTexture's alpha (cells).
    stripes = checker(64, 4, (255, 255, 255), (60, 120, 255))
    stripes[..., 0] = np.where(np.arange(64)[None, :] // 16 % 2 == 0, 255, 60)
    stripes[..., 1] = stripes[..., 0]
    fuzz = checker(64, 8, (0, 0, 0), (0, 0, 0))
    fuzz[..., 3] = np.where(checker(64, 8)[..., 0] > 128, 255, 60)
    for i, (colour, rough) in enumerate((((0, 0, 0), 0.5), ((1, 1, 1), 0.3), ((1, 1, 1), 0.8),
                                          ((1.0, 0.6, 0.2), 0.5), ((1, 1, 1), 1.0))):
        x = {"sheenColorFactor": list(colour), "sheenRoughnessFactor": rough}
        if i == 4:
            x["sheenColorTexture"] = {"index": d.image(stripes)}
            x["sheenRoughnessTexture"] = {"index": d.image(fuzz)}
        m = pbr((0.25, 0.02, 0.03), 0, 0.7, extensions={"KHR_materials_sheen": x})
        d.node(mesh=d.mesh([d.prim(sphere(0.22), d.material(m))]), translation=[(i - 2) * 0.55, 0, 0])
    d.uses("KHR_materials_sheen")


def transmission(d):
    # Five glass spheres before a checker wall: thin-walled (only its reflections), a solid ball
    # of IOR 1.5 (the wall refracted, upside down), the same absorbing to amber over 0.2 m
    # (KHR_materials_volume), frosted (roughness 0.5), and one whose transmissionTexture lets
    # light through in stripes only (the rest a white diffuse).
    wall = pbr((1, 1, 1), 0, 0.8)
    wall["pbrMetallicRoughness"]["baseColorTexture"] = {
        "index": d.image(checker(64, 8, (255, 200, 40), (20, 60, 160)))}
    wall = d.material(wall)
    d.node(mesh=d.mesh([d.prim(quad(3.2, 1.2), wall)]), translation=[0, 0, -0.5])
    stripes = checker(64, 1, (0, 0, 0), (0, 0, 0))
    stripes[..., 0] = np.where(np.arange(64)[None, :] // 8 % 2 == 0, 255, 0)
    r = 0.22
    for i, (volume, rough, texture) in enumerate(((None, 0.0, False),
                                                  ({"thicknessFactor": 2 * r}, 0.0, False),
                                                  ({"thicknessFactor": 2 * r, "attenuationDistance": 0.2,
                                                    "attenuationColor": [1.0, 0.6, 0.15]}, 0.0, False),
                                                  ({"thicknessFactor": 2 * r}, 0.5, False),
                                                  (None, 0.1, True))):
        x = {"transmissionFactor": 1.0}
        if texture:
            x["transmissionTexture"] = {"index": d.image(stripes)}
        ext = {"KHR_materials_transmission": x}
        if volume:
            ext["KHR_materials_volume"] = volume
        m = pbr((1, 1, 1), 0, rough, extensions=ext)
        d.node(mesh=d.mesh([d.prim(sphere(r), d.material(m))]), translation=[(i - 2) * 0.58, 0, 0])
    d.uses("KHR_materials_transmission", "KHR_materials_volume")


def alpha_modes(d):
    # OPAQUE ignores alpha 0.5, MASK cuts the checker's dark cells (alpha from its brightness),
    # BLEND shows the sphere behind through alpha 0.5.
    pix = checker(64, 4, (255, 255, 255), (0, 0, 0))
    pix[..., 3] = pix[..., 0]
    t = d.image(pix)
    for i, mode in enumerate(("OPAQUE", "MASK", "BLEND")):
        m = pbr((0.9, 0.5, 0.1, 0.5), alphaMode=mode)
        if mode == "MASK":
            m["pbrMetallicRoughness"]["baseColorTexture"] = {"index": t}
            m["pbrMetallicRoughness"]["baseColorFactor"] = [0.9, 0.5, 0.1, 1]
        d.node(mesh=d.mesh([d.prim(quad(), d.material(m))]), translation=[(i - 1) * 1.1, 0, 0])
    d.node(mesh=d.mesh([d.prim(sphere(0.3), d.material(pbr((0.1, 0.3, 0.9))))]),
           translation=[1.1, 0, -0.6])


def punctual_lights(d):
    floor = d.material(pbr((0.8, 0.8, 0.8), 0, 0.7))
    # The floor fills the view, so that the exposure is the lit floor's.
    d.node(mesh=d.mesh([d.prim(quad(8, 8), floor)]), rotation=[-math.sqrt(0.5), 0, 0, math.sqrt(0.5)])
    d.j["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.05}}]
    eye = np.array([0.0, 1.6, 2.0])
    d.node(camera=0, translation=list(eye), rotation=look_at(eye, np.array([0, 0, 0])))
    d.node(mesh=d.mesh([d.prim(sphere(0.3), d.material(pbr((0.9, 0.9, 0.9))))]), translation=[0, 0.3, 0])
    d.j["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"type": "point", "color": [1, 0.4, 0.2], "intensity": 3},
        {"type": "spot", "color": [0.3, 0.5, 1], "intensity": 12, "spot": {"outerConeAngle": 0.6}}]}}
    d.node(translation=[0.8, 0.6, 0.5], extensions={"KHR_lights_punctual": {"light": 0}})
    d.node(translation=[-0.6, 1.5, 0.3], rotation=[-math.sqrt(0.5), 0, 0, math.sqrt(0.5)],
           extensions={"KHR_lights_punctual": {"light": 1}})
    d.uses("KHR_lights_punctual")


def camera(d):
    d.j["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05}}]
    eye = np.array([1.5, 1.0, 2.5])
    d.node(camera=0, translation=list(eye), rotation=look_at(eye, np.array([0, 0, -0.6])))
    for i in range(3):
        d.node(mesh=d.mesh([d.prim(sphere(0.25), d.material(pbr((0.3 * i, 0.5, 0.9 - 0.3 * i))))]),
               translation=[i * 0.6 - 0.6, 0, -i * 0.6])


# Broken on purpose: the gallery shows each refused with the loader's reason.
def broken_index(d):
    basic(d)
    d.j["meshes"][0]["primitives"][0]["material"] = 7


def broken_schema(d):
    basic(d)
    d.j["nodes"][0]["scale"] = "not a number"


def broken_required(d):
    basic(d)
    d.uses("KHR_not_an_extension", required=True)


def many_meshes(d, n):
    # n nodes on a square grid, each drawing a distinct mesh (a sphere of its own radius): what
    # loading a large asset costs when nothing is shared.
    m = d.material(pbr((0.7, 0.7, 0.7)))
    side = int(math.ceil(math.sqrt(n)))
    for i in range(n):
        mesh = d.mesh([d.prim(sphere(0.3 + 0.1 * (i % 97) / 97, 12), m)])
        d.node(mesh=mesh, translation=[(i % side) * 1.0, 0, (i // side) * 1.0])


MODELS = [basic, metal_rough_spheres, primitive_modes, lines_and_points, texture_transform,
          texcoord_sets, vertex_colors, quantized, morph_targets, skin, instancing, variants, unlit,
          emissive_label, clearcoat, sheen, transmission, ior_specular, specular_glossiness, alpha_modes,
          punctual_lights, camera, broken_index, broken_schema, broken_required]


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) >= 2 else 2
    if "--list" in argv:
        print("\n".join(m.__name__ for m in MODELS))
        return 0
    out = argv[1]
    os.makedirs(out, exist_ok=True)
    if "--many" in argv:
        n = int(argv[argv.index("--many") + 1])
        d = Doc()
        many_meshes(d, n)
        d.write(os.path.join(out, f"many_meshes_{n}.gltf"), external=True)
        print(f"gltf_models: wrote many_meshes_{n}.gltf ({n} nodes and meshes) to {out}")
        return 0
    for make in MODELS:
        d = Doc()
        make(d)
        d.write(os.path.join(out, make.__name__ + ".gltf"))
    print(f"gltf_models: wrote {len(MODELS)} models to {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
