"""Small edits of a glTF document held as JSON (dicts and lists)."""
import base64
import json
import os
import struct
import tempfile

FLOAT, UNSIGNED_INT = 5126, 5125
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963

EXTENSION = "VKDR_participating_media"

# What the glTF exporter writes for a material that vkdiffrender would refuse on a
# surface (refraction) or read as a medium.
TRANSMISSION_EXTENSIONS = ("KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_ior")


def medium_json(medium):
    """A mappings.Medium as VKDR_participating_media writes it."""
    entry = {"sigma_a": list(medium.sigma_a), "sigma_s": list(medium.sigma_s), "g": medium.g}
    if any(c > 0.0 for c in medium.emission):
        entry["emission"] = list(medium.emission)
    return entry


def use_extension(doc, name):
    used = doc.setdefault("extensionsUsed", [])
    if name not in used:
        used.append(name)


def drop_unused_extensions(doc):
    """extensionsUsed may list only extensions that occur; edits may have removed some."""
    text = json.dumps({k: v for k, v in doc.items() if k not in ("extensionsUsed", "extensionsRequired")})
    for key in ("extensionsUsed", "extensionsRequired"):
        if key in doc:
            doc[key] = [name for name in doc[key] if f'"{name}"' in text]
            if not doc[key]:
                del doc[key]


def add_mesh_node(doc, name, positions, triangles, material):
    """A node with a mesh of world-space POSITIONs and one material, stored in a buffer of
    its own as a data URI so that the exporter's .bin stays as written."""
    vertex_bytes = b"".join(struct.pack("<3f", *p) for p in positions)
    index_bytes = b"".join(struct.pack("<3I", *t) for t in triangles)
    data = vertex_bytes + index_bytes
    buffer = len(doc.setdefault("buffers", []))
    doc["buffers"].append({"byteLength": len(data),
                           "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()})
    views = doc.setdefault("bufferViews", [])
    views.append({"buffer": buffer, "byteOffset": 0, "byteLength": len(vertex_bytes), "target": ARRAY_BUFFER})
    views.append({"buffer": buffer, "byteOffset": len(vertex_bytes), "byteLength": len(index_bytes),
                  "target": ELEMENT_ARRAY_BUFFER})
    accessors = doc.setdefault("accessors", [])
    accessors.append({"bufferView": len(views) - 2, "componentType": FLOAT, "count": len(positions), "type": "VEC3",
                      "min": [min(p[i] for p in positions) for i in range(3)],
                      "max": [max(p[i] for p in positions) for i in range(3)]})
    accessors.append({"bufferView": len(views) - 1, "componentType": UNSIGNED_INT, "count": 3 * len(triangles),
                      "type": "SCALAR"})
    materials = doc.setdefault("materials", [])
    materials.append(material)
    meshes = doc.setdefault("meshes", [])
    meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": len(accessors) - 2},
                                                  "indices": len(accessors) - 1, "material": len(materials) - 1}]})
    nodes = doc.setdefault("nodes", [])
    nodes.append({"name": name, "mesh": len(meshes) - 1})
    scene = doc.setdefault("scenes", [{"nodes": []}])[doc.get("scene", 0)]
    scene.setdefault("nodes", []).append(len(nodes) - 1)


def new_file_mode(path):
    """The permissions of the file at PATH, or those a new file gets (0666 less the umask):
    mkstemp's 0600 would hide the written file from other users."""
    try:
        return os.stat(path).st_mode & 0o777
    except FileNotFoundError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


def write_atomically(path, doc, mode_of=None):
    """Write through a temporary file and a rename, so that a failure leaves the old file;
    with the permissions of the file at MODE_OF (by default PATH) where there is one."""
    directory = os.path.dirname(os.path.abspath(path))
    handle, temporary = tempfile.mkstemp(dir=directory, suffix=".tmp")
    try:
        os.chmod(temporary, new_file_mode(mode_of or path))
        with os.fdopen(handle, "w", encoding="utf-8") as f:
            json.dump(doc, f, indent=1)
        os.replace(temporary, path)
    except BaseException:
        os.unlink(temporary)
        raise
