#!/usr/bin/env python3
"""Writes content/models/glint_sample.gltf: a 4 m x 4 m floor with a glinty material (GLIMMER_materials_glint),
a plain painted box on it (not glinty), a camera, and KHR_lights_punctual spot + directional lights.
UVs of the floor span [0, 1] over 4 m, so 16 m^2 of surface per unit UV area (the loader measures it)."""
import base64, json, struct, pathlib

def quad_floor(h):
    p = [(-h, 0, -h), (h, 0, -h), (h, 0, h), (-h, 0, h)]
    n = [(0, 1, 0)] * 4
    uv = [(0, 0), (1, 0), (1, 1), (0, 1)]
    idx = [0, 2, 1, 0, 3, 2]
    return p, n, uv, idx

def box(s, y0):
    p, n, uv, idx = [], [], [], []
    faces = [((1, 0, 0), (0, 0, -1), (0, 1, 0)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)), ((0, 1, 0), (1, 0, 0), (0, 0, -1)),
             ((0, -1, 0), (1, 0, 0), (0, 0, 1)), ((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (-1, 0, 0), (0, 1, 0))]
    for nn, u, v in faces:
        base = len(p)
        for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            c = [s * (nn[i] + a * u[i] + b * v[i]) for i in range(3)]
            c[1] += y0 + s
            p.append(tuple(c)); n.append(nn); uv.append(((a + 1) / 2, (1 - b) / 2))
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return p, n, uv, idx

meshes = [quad_floor(2.0), box(0.4, 0.0)]
blob = b""
views, accessors = [], []
def add(data, fmt, count, comp, typ, target, minmax=None):
    global blob
    while len(blob) % 4: blob += b"\0"
    off = len(blob)
    blob += b"".join(struct.pack(fmt, *d) if isinstance(d, tuple) else struct.pack(fmt, d) for d in data)
    views.append({"buffer": 0, "byteOffset": off, "byteLength": len(blob) - off, "target": target})
    a = {"bufferView": len(views) - 1, "componentType": comp, "count": count, "type": typ}
    if minmax: a["min"], a["max"] = minmax
    accessors.append(a)
    return len(accessors) - 1
gl_meshes = []
for mi, (p, n, uv, idx) in enumerate(meshes):
    mins = [min(v[i] for v in p) for i in range(3)]; maxs = [max(v[i] for v in p) for i in range(3)]
    ap = add(p, "<3f", len(p), 5126, "VEC3", 34962, (mins, maxs))
    an = add(n, "<3f", len(n), 5126, "VEC3", 34962)
    at = add(uv, "<2f", len(uv), 5126, "VEC2", 34962)
    ai = add(idx, "<I", len(idx), 5125, "SCALAR", 34963)
    gl_meshes.append({"name": ["floor", "box"][mi], "primitives": [
        {"attributes": {"POSITION": ap, "NORMAL": an, "TEXCOORD_0": at}, "indices": ai, "material": mi}]})

doc = {
    "asset": {"version": "2.0", "generator": "tools/make_glint_sample.py"},
    "extensionsUsed": ["GLIMMER_materials_glint", "KHR_lights_punctual"],
    "extensions": {"KHR_lights_punctual": {"lights": [
        {"name": "spot", "type": "spot", "color": [1.0, 0.9, 0.8], "intensity": 40.0,
         "spot": {"innerConeAngle": 0.25, "outerConeAngle": 0.5}},
        {"name": "moon", "type": "directional", "color": [0.6, 0.7, 1.0], "intensity": 0.3}]}},
    "materials": [
        {"name": "glitter_floor",
         "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.75, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.55},
         "extensions": {"GLIMMER_materials_glint": {"density": 4e5, "angularSize": 0.02, "color": [1.0, 0.95, 0.85]}}},
        {"name": "painted_box",
         "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.1, 0.08, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.5}}],
    "meshes": gl_meshes,
    "cameras": [{"name": "view", "type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05, "aspectRatio": 1.0}}],
    "nodes": [
        {"name": "floor", "mesh": 0},
        {"name": "box", "mesh": 1, "translation": [0.6, 0.0, -0.4]},
        # Spot above and in front, shining down at the floor (-Z of the node after a -60 degree turn about x).
        {"name": "spot", "translation": [-0.5, 2.5, 1.5], "rotation": [-0.5, 0.0, 0.0, 0.8660254],
         "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "moon", "rotation": [-0.3826834, 0.0, 0.0, 0.9238795], "extensions": {"KHR_lights_punctual": {"light": 1}}},
        # Camera at (0, 1.6, 3.6) looking down at the floor (-Z turned 25 degrees down).
        {"name": "view", "camera": 0, "translation": [0.0, 1.6, 3.6], "rotation": [-0.2164396, 0.0, 0.0, 0.9762960]}],
    "scenes": [{"nodes": [0, 1, 2, 3, 4]}],
    "scene": 0,
    "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    "bufferViews": views,
    "accessors": accessors,
}
out = pathlib.Path(__file__).resolve().parent.parent / "content" / "models" / "glint_sample.gltf"
out.write_text(json.dumps(doc, indent=1) + "\n")
print(out)
