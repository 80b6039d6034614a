#!/usr/bin/env python3
"""Writes small files of every format the loaders read into FOLDER/{obj,ply,gltf,pbrt}: the seed corpora
of the mesh and pbrt harnesses (scripts/fuzz.sh). Generated here, so that no seed is a copy of someone's mesh."""
import base64
import json
import struct
import sys
from pathlib import Path

CUBE = [(x, y, z) for x in (0.0, 1.0) for y in (0.0, 1.0) for z in (0.0, 1.0)]
QUADS = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
TRIANGLES = [t for q in QUADS for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]


def obj_seeds(out):
    mtl = "newmtl red\nKd 0.8 0.1 0.1\nnewmtl blue\nKd 0.1 0.1 0.8\nmap_Kd missing.png\n"
    verts = "".join(f"v {x} {y} {z}\n" for x, y, z in CUBE)
    quads = "".join(f"f {a + 1} {b + 1} {c + 1} {d + 1}\n" for a, b, c, d in QUADS)
    (out / "cube.obj").write_text("mtllib cube.mtl\no cube\n" + verts + "usemtl red\n" + quads + "\0" + mtl)
    uvs = "vt 0 0\nvt 1 0\nvt 1 1\n"
    normals = "vn 0 0 1\n"
    (out / "attributes.obj").write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n" + uvs + normals +
                                        "g tri\ns 1\nf 1/1/1 2/2/1 3/3/1\nf -4//1 -2//1 -1//1\nf 1 2 3 4\n")
    (out / "polygon.obj").write_text("".join(f"v {i} {i * i % 7} 0\n" for i in range(8)) +
                                     "usemtl blue\nf 1 2 3 4 5 6 7 8\nl 1 2\np 3\n\0" + mtl)


def ply_header(fmt, extra=""):
    return (f"ply\nformat {fmt} 1.0\ncomment generated\nelement vertex {len(CUBE)}\n"
            "property float x\nproperty float y\nproperty float z\n"
            f"{extra}element face {len(QUADS)}\nproperty list uchar int vertex_indices\nend_header\n")


def ply_seeds(out):
    body = "".join(f"{x} {y} {z} {x} {y}\n" for x, y, z in CUBE)
    body += "".join(f"4 {a} {b} {c} {d}\n" for a, b, c, d in QUADS)
    (out / "ascii.ply").write_text(ply_header("ascii", "property float u\nproperty float v\n") + body)
    for fmt, order in (("binary_little_endian", "<"), ("binary_big_endian", ">")):
        data = b"".join(struct.pack(order + "3f", *p) for p in CUBE)
        data += b"".join(struct.pack(order + "B4i", 4, *q) for q in QUADS)
        (out / f"{fmt}.ply").write_bytes(ply_header(fmt).encode() + data)
    extra = ("element vertex 3\nproperty double x\nproperty double y\nproperty double z\nproperty uchar red\n"
             "element edge 1\nproperty int a\nproperty int b\n"
             "element face 1\nproperty list ushort uint vertex_index\nend_header\n")
    data = struct.pack("<3dB", 0, 0, 0, 255) + struct.pack("<3dB", 1, 0, 0, 0) + struct.pack("<3dB", 0, 1, 0, 9)
    data += struct.pack("<2i", 0, 1) + struct.pack("<H3I", 3, 0, 1, 2)
    (out / "doubles.ply").write_bytes(b"ply\nformat binary_little_endian 1.0\n" + extra.encode() + data)


def gltf_model(buffer_uri=None):
    positions = b"".join(struct.pack("<3f", *p) for p in CUBE)
    indices = b"".join(struct.pack("<H", i) for t in TRIANGLES for i in t)
    blob = positions + indices
    buffer = {"byteLength": len(blob)}
    if buffer_uri:
        buffer["uri"] = buffer_uri + base64.b64encode(blob).decode()
    model = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "children": [1], "translation": [1, 0, 0]},
                  {"mesh": 0, "matrix": [1, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1, 0, 0, 0, 3, 1]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "materials": [{"name": "paint", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.5, 0.1, 1]}}],
        "buffers": [buffer],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(positions)},
                        {"buffer": 0, "byteOffset": len(positions), "byteLength": len(indices)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(CUBE), "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 1]},
                      {"bufferView": 1, "componentType": 5123, "count": len(indices) // 2, "type": "SCALAR"}],
    }
    return model, blob


def gltf_seeds(out):
    model, _ = gltf_model("data:application/octet-stream;base64,")
    (out / "embedded.gltf").write_text(json.dumps(model))
    model, blob = gltf_model()
    text = json.dumps(model).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(blob), 0x004E4942) + blob
    (out / "cube.glb").write_bytes(struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks)


def pbrt_seeds(out):
    points = " ".join(f"{x} {y} {z}" for x, y, z in CUBE)
    indices = " ".join(str(i) for t in TRIANGLES for i in t)
    cube = f'Shape "trianglemesh" "integer indices" [ {indices} ] "point P" [ {points} ]\n'
    (out / "v3.pbrt").write_text(
        'LookAt 3 2 -4  0.5 0.5 0.5  0 1 0\nCamera "perspective" "float fov" [ 40 ] "float lensradius" 0.01\n'
        'Film "image" "integer xresolution" 64 "integer yresolution" [ 48 ]\nSampler "sobol" "integer pixelsamples" 4\n'
        'Integrator "path" "integer maxdepth" [ 5 ]\nPixelFilter "gaussian"\nWorldBegin\n'
        'Texture "wood" "spectrum" "imagemap" "string filename" "wood.tga" "bool trilinear" "true"\n'
        'Texture "check" "spectrum" "checkerboard" "rgb tex1" [1 1 1] "rgb tex2" [0 0 0] "float uscale" 8\n'
        'MakeNamedMaterial "red" "string type" [ "substrate" ] "rgb Kd" [ 0.8 0.1 0.1 ] "rgb Ks" [ 0.04 0.04 0.04 ]'
        ' "float uroughness" 0.1 "float vroughness" 0.1 "bool remaproughness" "false"\n'
        'MakeNamedMaterial "gold" "string type" "metal" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k"\n'
        'MakeNamedMaterial "clear" "string type" "glass" "float index" 1.5\n'
        'MakeNamedMaterial "hidden" "string type" "uber" "rgb opacity" [ 0 0 0 ]\n'
        'LightSource "point" "rgb I" [ 5 5 5 ] "point from" [ 0 4 0 ]\nLightSource "distant" "point to" [ 0 -1 0 ]\n'
        'LightSource "infinite" "rgb L" [ 0.2 0.3 0.4 ]\n'
        'AttributeBegin\n  AreaLightSource "diffuse" "rgb L" [ 4 4 4 ]\n'
        '  Shape "trianglemesh" "integer indices" [ 0 1 2 0 2 3 ] "point P" [ 0 3 0 1 3 0 1 3 1 0 3 1 ]'
        ' "normal N" [ 0 -1 0 0 -1 0 0 -1 0 0 -1 0 ]\nAttributeEnd\n'
        'AttributeBegin\n  NamedMaterial "red"\n  Translate 1 0 0\n  Rotate 30 0 1 0\n  Scale 1 2 1\n  ' + cube +
        'AttributeEnd\nAttributeBegin\n  Material "matte" "texture Kd" "check"\n  Shape "sphere" "float radius" 0.5\nAttributeEnd\n'
        'NamedMaterial "hidden"\n' + cube + 'NamedMaterial "gold"\nInclude "more.pbrt"\n'
        'Shape "plymesh" "string filename" "models/mesh.ply"\nWorldEnd\n')
    (out / "v4.pbrt").write_text(
        'Scale -1 1 1\nLookAt 0 1 -5 0 1 0 0 1 0\nCamera "perspective" "float fov" 30\nColorSpace "srgb"\nOption "bool wavefront" true\n'
        'WorldBegin\nAttribute "shape" "float radius" 2\nMaterial "coateddiffuse" "rgb reflectance" [ 0.2 0.5 0.2 ] "float roughness" 0.1\n'
        'Shape "bilinearmesh" "point3 P" [ 0 0 0 1 0 0 0 1 0 1 1 0 ]\nMaterial "conductor" "rgb reflectance" [ 0.9 0.6 0.3 ]\n'
        'Shape "sphere"\nMaterial "dielectric" "spectrum eta" "glass-BK7"\nShape "sphere" "float radius" 0.3\n'
        'Material "diffuse" "spectrum reflectance" [ 400 0.5 700 0.8 ]\nAreaLightSource "diffuse" "blackbody L" [ 6500 ] "float scale" 3\n'
        'Shape "sphere" "float radius" 0.1\nMakeNamedMedium "fog" "string type" "homogeneous"\nMaterial "interface"\n' + cube)
    (out / "objects.pbrt").write_text(
        'Camera "perspective"\nWorldBegin\nCoordinateSystem "origin"\nObjectBegin "box"\n' + cube + 'ObjectEnd\n'
        'TransformBegin\nTranslate 2 0 0\nObjectInstance "box"\nTransformEnd\nCoordSysTransform "origin"\n'
        'ReverseOrientation\nConcatTransform [ 1 0 0 0 0 1 0 0 0 0 1 0 0 0 5 1 ]\nObjectInstance "box"\n'
        'Transform [ 2 0 0 0 0 2 0 0 0 0 2 0 1 1 1 1 ]\nIdentity\nObjectInstance "box"\n')


def main():
    root = Path(sys.argv[1])
    for name, make in (("obj", obj_seeds), ("ply", ply_seeds), ("gltf", gltf_seeds), ("pbrt", pbrt_seeds)):
        folder = root / name
        folder.mkdir(parents=True, exist_ok=True)
        make(folder)


if __name__ == "__main__":
    main()
