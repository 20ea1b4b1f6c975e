#!/usr/bin/env python3
# Writes the seeds of the document_write fuzz target (tests/fuzz/corpus/document_write), and of
# packaged_document, json_spans and xml_tags beside it: small
# synthetic files of every format and of the glTF and 3MF features the readers handle. Each seed
# is one byte naming the format (0 obj, 1 off, 2 ply, 3 stl, 4 glb, 5 gltf, 6 3mf), then the file.
# Usage: make_document_seeds.py OUT_DIR [tetra.drc]  (a Draco stream of a tetrahedron, optional)
import base64, io, json, os, struct, sys, zipfile

out = sys.argv[1]
V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
F = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]

def seed(name, fmt, data):
    if isinstance(data, str):
        data = data.encode()
    with open(f"{out}/{name}", "wb") as f:
        f.write(bytes([fmt]) + data)

seed("tetra.obj", 0, "mtllib a.mtl\no t\n" + "".join(f"v {x} {y} {z} 0.5 0.5 0.5\n" for x, y, z in V) +
     "vt 0 0\nvt 1 0\nvn 0 0 1\ng g1\nusemtl m\ns 1\n" + "".join(f"f {a+1}/1/1 {b+1}/2/1 {c+1}/1/1\n" for a, b, c in F) + "l 1 2\n")
seed("quad.obj", 0, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nf 1 2 3 4\nf -5 -4 -1\n")
seed("tetra.off", 1, "NOFF\n# c\n4 4 0\n" + "".join(f"{x} {y} {z} 0 0 1\n" for x, y, z in V) + "".join(f"3 {a} {b} {c}\n" for a, b, c in F))
ply_head = ("ply\nformat {}\ncomment c\nobj_info o\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
            "property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\nelement face 4\n"
            "property list uchar int vertex_indices\nend_header\n")
seed("tetra_ascii.ply", 2, ply_head.format("ascii 1.0") + "".join(f"{x} {y} {z} 0 0 1 7\n" for x, y, z in V) +
     "".join(f"3 {a} {b} {c}\n" for a, b, c in F))
body = b"".join(struct.pack("<6fB", x, y, z, 0, 0, 1, 7) for x, y, z in V) + b"".join(struct.pack("<B3i", 3, *f) for f in F)
seed("tetra_binary.ply", 2, ply_head.format("binary_little_endian 1.0").encode() + body)
stl = b"solid binary header".ljust(80, b" ") + struct.pack("<I", len(F))
for a, b, c in F:
    stl += struct.pack("<12fH", 0, 0, 0, *V[a], *V[b], *V[c], 0x1234)
seed("tetra_binary.stl", 3, stl)
seed("tetra_ascii.stl", 3, "solid t\n" + "".join(
    "facet normal 0 0 0\nouter loop\n" + "".join(f"vertex {V[i][0]} {V[i][1]} {V[i][2]}\n" for i in f) + "endloop\nendfacet\n" for f in F) + "endsolid t\n")

def glb(j, bin_):
    js = json.dumps(j).encode()
    js += b" " * (-len(js) % 4)
    bin_ += b"\0" * (-len(bin_) % 4)
    body = struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(bin_), 0x004E4942) + bin_
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body

positions = b"".join(struct.pack("<3f", *v) for v in V)
normals = b"".join(struct.pack("<3f", 0, 0, 1) for _ in V)
indices = b"".join(struct.pack("<3H", *f) for f in F)
bin_ = positions + normals + indices
base = {"asset": {"version": "2.0"}, "buffers": [{"byteLength": len(bin_)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 24}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]},
                      {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                      {"bufferView": 2, "componentType": 5123, "count": 12, "type": "SCALAR"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
        "nodes": [{"mesh": 0, "translation": [1, 2, 3]}, {"mesh": 0, "rotation": [0, 0, 0.7071068, 0.7071068], "children": [2]},
                  {"matrix": [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1]}],
        "scenes": [{"nodes": [0, 1]}], "scene": 0}
seed("instanced.glb", 4, glb(base, bin_))
# Interleaved positions and normals, and a sparse accessor over the positions.
inter = b"".join(struct.pack("<6f", *v, 0, 0, 1) for v in V) + indices + struct.pack("<H", 2) + b"\0\0" + struct.pack("<3f", 0, 2, 0)
j = {"asset": {"version": "2.0"}, "buffers": [{"byteLength": len(inter)}],
     "bufferViews": [{"buffer": 0, "byteLength": 96, "byteStride": 24}, {"buffer": 0, "byteOffset": 96, "byteLength": 24},
                     {"buffer": 0, "byteOffset": 120, "byteLength": 2}, {"buffer": 0, "byteOffset": 124, "byteLength": 12}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 2, 1],
                    "sparse": {"count": 1, "indices": {"bufferView": 2, "componentType": 5123}, "values": {"bufferView": 3}}},
                   {"bufferView": 0, "byteOffset": 12, "componentType": 5126, "count": 4, "type": "VEC3"},
                   {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}], "nodes": [{"mesh": 0}]}
seed("interleaved_sparse.glb", 4, glb(j, inter))
# KHR_mesh_quantization: u16 positions from 0, i8 normalized normals, the node dequantizing.
q = b"".join(struct.pack("<3H", *(int(c * 1000) for c in v)) + b"\0\0" for v in V)
qn = b"".join(struct.pack("<3b", 0, 0, 127) + b"\0" for _ in V)
qbin = q + qn + indices
j = {"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_mesh_quantization"], "extensionsRequired": ["KHR_mesh_quantization"],
     "buffers": [{"byteLength": len(qbin)}],
     "bufferViews": [{"buffer": 0, "byteLength": 32, "byteStride": 8}, {"buffer": 0, "byteOffset": 32, "byteLength": 16, "byteStride": 4},
                     {"buffer": 0, "byteOffset": 48, "byteLength": 24}],
     "accessors": [{"bufferView": 0, "componentType": 5123, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1000, 1000, 1000]},
                   {"bufferView": 1, "componentType": 5120, "normalized": True, "count": 4, "type": "VEC3"},
                   {"bufferView": 2, "componentType": 5123, "count": 12, "type": "SCALAR"}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
     "nodes": [{"mesh": 0, "scale": [0.001, 0.001, 0.001], "translation": [-0.5, 0, 0]}]}
seed("quantized.glb", 4, glb(j, qbin))
j = dict(base)
j["buffers"] = [{"byteLength": len(bin_), "uri": "data:application/octet-stream;base64," + base64.b64encode(bin_).decode()}]
seed("data_uri.gltf", 5, json.dumps(j, indent=1))
if len(sys.argv) > 2:
    drc = open(sys.argv[2], "rb").read()
    j = {"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_draco_mesh_compression"],
         "extensionsRequired": ["KHR_draco_mesh_compression"], "buffers": [{"byteLength": len(drc) + (-len(drc) % 4)}],
         "bufferViews": [{"buffer": 0, "byteLength": len(drc)}],
         "accessors": [{"componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]},
                       {"componentType": 5123, "count": 12, "type": "SCALAR"}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1,
                                     "extensions": {"KHR_draco_mesh_compression": {"bufferView": 0, "attributes": {"POSITION": 0}}}}]}],
         "nodes": [{"mesh": 0}]}
    seed("draco.glb", 4, glb(j, drc))

model = ('<?xml version="1.0" encoding="UTF-8"?>\n<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">\n'
         '<metadata name="Title">t</metadata><resources><object id="1" type="model"><mesh><vertices>' +
         "".join(f'<vertex x="{x}" y="{y}" z="{z}"/>' for x, y, z in V) + "</vertices><triangles>" +
         "".join(f'<triangle v1="{a}" v2="{b}" v3="{c}"/>' for a, b, c in F) + "</triangles></mesh></object>"
         '<object id="2"><components><component objectid="1" transform="1 0 0 0 1 0 0 0 1 5 0 0"/></components></object>'
         '</resources><build><item objectid="1" transform="2 0 0 0 2 0 0 0 2 0 0 1"/><item objectid="2"/></build></model>')
buffer = io.BytesIO()
with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as z:
    z.writestr("[Content_Types].xml", '<?xml version="1.0"?><Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
               '<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
               '<Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>')
    z.writestr("_rels/.rels", '<?xml version="1.0"?><Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
               '<Relationship Target="/3D/3dmodel.model" Id="r0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>')
    z.writestr("3D/3dmodel.model", model)
seed("components.3mf", 6, buffer.getvalue())

# The seeds of the targets beside it: packaged_document (one byte, 0 gltf, 1 obj, 2 3mf, 3 glb,
# then a ZIP of the file and its companions, or the file alone), json_spans and xml_tags (text).
corpus = os.path.dirname(os.path.abspath(out))
def target_seed(target, name, data, fmt=None):
    os.makedirs(f"{corpus}/{target}", exist_ok=True)
    data = data.encode() if isinstance(data, str) else data
    with open(f"{corpus}/{target}/{name}", "wb") as f:
        f.write((bytes([fmt]) if fmt is not None else b"") + data)

def zipped(files):
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as z:
        for name, data in files.items():
            z.writestr(name, data)
    return buffer.getvalue()

external = dict(base, buffers=[{"byteLength": len(bin_), "uri": "tetra.bin"}])
target_seed("packaged_document", "gltf_with_bin.zip", zipped({"model/tetra.gltf": json.dumps(external), "model/tetra.bin": bin_}), 0)
obj = "mtllib tetra.mtl\n" + "".join(f"v {x} {y} {z}\n" for x, y, z in V) + "usemtl m\n" + "".join(f"f {a+1} {b+1} {c+1}\n" for a, b, c in F)
target_seed("packaged_document", "obj_with_mtl.zip", zipped({"tetra.obj": obj, "tetra.mtl": "newmtl m\nmap_Kd t.png\n", "t.png": b"\x89PNG"}), 1)
target_seed("packaged_document", "alone.obj", obj, 1)
target_seed("packaged_document", "components.3mf", buffer.getvalue(), 2)
target_seed("packaged_document", "instanced.glb.zip", zipped({"a.glb": glb(base, bin_)}), 3)
target_seed("json_spans", "gltf.json", json.dumps(base, indent=1))
target_seed("json_spans", "escapes.json", '{"a\\"b": [1, -2.5e3, true, null, "\\u00e9"], "": {}}')
target_seed("xml_tags", "model.xml", model)
target_seed("xml_tags", "comments.xml", '<?xml version="1.0"?><!-- c --><a x="1" y=\'2\'><![CDATA[<b>]]><c/></a>')
