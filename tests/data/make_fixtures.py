#!/usr/bin/env python3
"""Writes the hand-made glTF fixtures of tests/scenes_test.cpp into this folder (run from anywhere).

texture_transform.gltf: two quads (plain / KHR_texture_transform offset 0.5, scale 2 along u) sharing an 8x8
texture (left half red, right half green), an unused rotated material, and a camera "front" at z = 6.
Broken variants: bad_buffer (missing .bin), short_buffer (buffer shorter than its views), corrupt (truncated
JSON), undecodable_image (image bytes that are not a PNG, a required material extension), requires_draco.
"""
import base64, json, os, struct, zlib

os.chdir(os.path.dirname(os.path.abspath(__file__)))


def png(width, height, pixel):
    raw = b''.join(b'\x00' + b''.join(bytes(pixel(x, y)) for x in range(width)) for y in range(height))
    def chunk(tag, data):
        c = struct.pack('>I', len(data)) + tag + data
        return c + struct.pack('>I', zlib.crc32(tag + data) & 0xffffffff)
    return (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, 8, 6, 0, 0, 0))
            + chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b''))


# Two quads side by side (z = 0, facing +z), UV u along +x, v down (glTF convention).
positions, uvs, normals = [], [], []
for x0 in (-2.1, 0.1):
    for (x, y) in ((x0, -1), (x0 + 2, -1), (x0 + 2, 1), (x0, 1)):
        positions += [x, y, 0.0]
        uvs += [(x - x0) / 2, (1 - y) / 2]
        normals += [0.0, 0.0, 1.0]
indices = [0, 1, 2, 0, 2, 3]
blob = struct.pack('<12f', *positions[:12]) + struct.pack('<12f', *normals[:12]) + struct.pack('<8f', *uvs[:8])
blob2 = struct.pack('<12f', *positions[12:]) + struct.pack('<12f', *normals[12:]) + struct.pack('<8f', *uvs[8:])
data = blob + blob2 + struct.pack('<6H', *indices) + b'\x00\x00'
views = [{"buffer": 0, "byteOffset": o, "byteLength": l} for (o, l) in
         [(0, 48), (48, 48), (96, 32), (128, 48), (176, 48), (224, 32), (256, 12)]]


def acc(view, typ, count, mn=None, mx=None, comp=5126):
    a = {"bufferView": view, "componentType": comp, "count": count, "type": typ}
    if mn is not None:
        a["min"], a["max"] = mn, mx
    return a


accessors = [acc(0, "VEC3", 4, [-2.1, -1, 0], [-0.1, 1, 0]), acc(1, "VEC3", 4), acc(2, "VEC2", 4),
             acc(3, "VEC3", 4, [0.1, -1, 0], [2.1, 1, 0]), acc(4, "VEC3", 4), acc(5, "VEC2", 4),
             acc(6, "SCALAR", 6, comp=5123)]
texture_png = png(8, 8, lambda x, y: (255, 0, 0, 255) if x < 4 else (0, 255, 0, 255))
gltf = {
    "asset": {"version": "2.0", "generator": "hand-written for tests/scenes_test.cpp"},
    "extensionsUsed": ["KHR_texture_transform"],
    "extensionsRequired": ["KHR_texture_transform"],
    "scene": 0,
    "scenes": [{"nodes": [0, 1, 2]}],
    "nodes": [{"mesh": 0, "name": "plain"}, {"mesh": 1, "name": "transformed"},
              {"camera": 0, "name": "front", "translation": [0, 0, 6]}],
    "cameras": [{"type": "perspective", "name": "front", "perspective": {"yfov": 0.7853981634, "znear": 0.1, "aspectRatio": 1.0}}],
    "meshes": [{"name": "plain", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 6, "material": 0}]},
               {"name": "transformed", "primitives": [{"attributes": {"POSITION": 3, "NORMAL": 4, "TEXCOORD_0": 5}, "indices": 6, "material": 1}]}],
    "materials": [
        {"name": "plain", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0, "roughnessFactor": 1}},
        {"name": "transformed", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "extensions": {
            "KHR_texture_transform": {"offset": [0.5, 0.0], "scale": [2.0, 1.0]}}}, "metallicFactor": 0, "roughnessFactor": 1}},
        {"name": "rotated", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "extensions": {
            "KHR_texture_transform": {"rotation": 1.5707963268}}}}}],
    "textures": [{"source": 0, "sampler": 0}],
    "samplers": [{"magFilter": 9728, "minFilter": 9728}],
    "images": [{"uri": "data:image/png;base64," + base64.b64encode(texture_png).decode()}],
    "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
    "bufferViews": views,
    "accessors": accessors,
}


def write(name, document):
    with open(name, 'w') as f:
        json.dump(document, f, indent=1)


def variant(**changes):
    document = json.loads(json.dumps(gltf))
    document.update(changes)
    return document


write('texture_transform.gltf', gltf)
write('bad_buffer.gltf', variant(buffers=[{"byteLength": len(data), "uri": "missing_buffer.bin"}]))
write('short_buffer.gltf', variant(buffers=[{"byteLength": 64, "uri": "data:application/octet-stream;base64,"
                                             + base64.b64encode(data[:64]).decode()}]))
text = open('texture_transform.gltf').read()
open('corrupt.gltf', 'w').write(text[:len(text) // 3])
write('undecodable_image.gltf', variant(
    images=[{"uri": "data:image/png;base64," + base64.b64encode(b"this is not a PNG file").decode()}],
    extensionsUsed=["KHR_texture_transform", "KHR_materials_sheen"],
    extensionsRequired=["KHR_texture_transform", "KHR_materials_sheen"]))
write('requires_draco.gltf', variant(extensionsUsed=["KHR_draco_mesh_compression"],
                                     extensionsRequired=["KHR_draco_mesh_compression"]))
