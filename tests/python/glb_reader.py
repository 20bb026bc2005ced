"""An independent reader for glTF 2.0 binary files (.glb), for limsurf's tests.

It shares no code with limsurf's writer (src/limsurf/io/gltf.cpp) and needs only the
standard library and numpy, so the Python module's tests can check what limsurf writes
against the specification (https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html)
rather than against itself.

Usage::

    from glb_reader import read_glb, GlbError

    mesh = read_glb("surface.glb")        # a path, or the file's bytes
    mesh.positions                        # (P, 3) float32, as stored
    mesh.normals                          # (P, 3) float32, or None
    mesh.colors                           # (P, 4) or (P, 3) float32 in [0, 1] (linear), or None
    mesh.triangles                        # (T, 3) uint32
    mesh.attributes["_MEAN_CURVATURE"]    # every attribute by its glTF name
    mesh.gltf                             # the JSON chunk as a dict
    mesh.accessor_names["_MEAN_CURVATURE"]  # the accessor's "name", or None

Integer accessors marked ``normalized`` are returned as float32 in [0, 1]; everything else
keeps its stored dtype (little-endian). limsurf writes sRGB input colours as *linear*
values (glTF's COLOR_0 is linear): compare with the sRGB transfer function applied.

What ``read_glb`` checks (any violation raises ``GlbError``, a ``ValueError``, naming the rule):

* the header: magic ``glTF``, version 2, total length equal to the file's size;
* the chunks: first JSON (type 0x4E4F534A) padded with spaces (0x20) to a multiple of
  4 bytes, then at most one BIN (type 0x004E4942) with a length that is a multiple of 4,
  its padding zeros, nothing after it; the JSON is UTF-8 and parses;
* ``asset.version`` is "2.0"; ``scene``, ``scenes[].nodes`` and ``nodes[].mesh`` refer to
  existing objects;
* the GLB buffer (buffers[0] without ``uri``) exists when anything refers to it, and its
  ``byteLength`` is the BIN chunk's length or up to 3 bytes less;
* every bufferView lies inside its buffer, has ``target`` 34962 (ARRAY_BUFFER) or 34963
  (ELEMENT_ARRAY_BUFFER) when given, and a ``byteStride`` (when given) in [4, 252] and a
  multiple of 4;
* every accessor read has a known ``componentType`` and ``type``, no sparse storage,
  an offset (accessor plus bufferView) that is a multiple of its component size, and
  lies inside its bufferView; ``min`` and ``max``, when present, equal the data's
  component-wise extremes (compared as the stored type; required for POSITION);
* the primitive: ``mode`` 4 (TRIANGLES, the default), POSITION present as FLOAT VEC3,
  NORMAL (when present) FLOAT VEC3 of unit length (within ``normal_tolerance``),
  COLOR_0 (when present) VEC3/VEC4 of FLOAT, or normalized UNSIGNED_BYTE/UNSIGNED_SHORT,
  with values in [0, 1]; application-specific attributes start with "_" and are not
  UNSIGNED_INT; all attributes have the same count; vertex attributes sit in
  bufferViews with target ARRAY_BUFFER (when given) and have elements aligned to 4 bytes;
* the indices: SCALAR UNSIGNED_BYTE/UNSIGNED_SHORT/UNSIGNED_INT, not normalized, in a
  bufferView with target ELEMENT_ARRAY_BUFFER (when given), a count that is a multiple of
  3, every index below the number of vertices. Without indices the vertices are taken
  three by three.

It does not read images, textures, animations, skins, morph targets, extensions
(``extensionsRequired`` is refused) or external buffers (a ``uri``) — limsurf writes none.

Self-check: ``python3 glb_reader.py FILE.glb`` prints a summary or the first violation.
"""

from __future__ import annotations

import json
import os
import struct
import sys
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["GlbError", "GlbMesh", "read_glb", "read_accessor"]

GLB_MAGIC = 0x46546C67  # "glTF"
CHUNK_JSON = 0x4E4F534A  # "JSON"
CHUNK_BIN = 0x004E4942  # "BIN\0"
ARRAY_BUFFER = 34962
ELEMENT_ARRAY_BUFFER = 34963
MODE_TRIANGLES = 4

BYTE, UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT, UNSIGNED_INT, FLOAT = 5120, 5121, 5122, 5123, 5125, 5126
COMPONENT_DTYPES = {
    BYTE: np.dtype("<i1"),
    UNSIGNED_BYTE: np.dtype("<u1"),
    SHORT: np.dtype("<i2"),
    UNSIGNED_SHORT: np.dtype("<u2"),
    UNSIGNED_INT: np.dtype("<u4"),
    FLOAT: np.dtype("<f4"),
}
TYPE_COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT2": 4, "MAT3": 9, "MAT4": 16}


class GlbError(ValueError):
    """A file that is not a valid glTF 2.0 binary, or breaks one of the rules checked."""


@dataclass
class GlbMesh:
    """One primitive of a .glb file, its arrays decoded."""

    gltf: dict[str, Any]
    positions: np.ndarray
    triangles: np.ndarray
    normals: np.ndarray | None = None
    colors: np.ndarray | None = None
    attributes: dict[str, np.ndarray] = field(default_factory=dict)
    accessor_names: dict[str, str | None] = field(default_factory=dict)
    header_length: int = 0
    json_chunk_length: int = 0
    bin_chunk_length: int = 0


def _fail(message: str) -> None:
    raise GlbError(message)


def _split_chunks(data: bytes) -> tuple[dict[str, Any], bytes | None, int, int]:
    if len(data) < 12:
        _fail(f"file of {len(data)} bytes is shorter than the 12-byte GLB header")
    magic, version, length = struct.unpack_from("<III", data, 0)
    if magic != GLB_MAGIC:
        _fail(f"magic is 0x{magic:08X}, expected 0x46546C67 ('glTF')")
    if version != 2:
        _fail(f"GLB version is {version}, expected 2")
    if length != len(data):
        _fail(f"header length is {length}, the file has {len(data)} bytes")
    offset = 12
    chunks: list[tuple[int, bytes, int]] = []
    while offset < len(data):
        if offset + 8 > len(data):
            _fail(f"truncated chunk header at byte {offset}")
        chunk_length, chunk_type = struct.unpack_from("<II", data, offset)
        start = offset + 8
        if chunk_length % 4 != 0:
            _fail(f"chunk at byte {offset} has length {chunk_length}, not a multiple of 4")
        if start + chunk_length > len(data):
            _fail(f"chunk at byte {offset} (length {chunk_length}) runs past the end of the file")
        chunks.append((chunk_type, data[start : start + chunk_length], offset))
        offset = start + chunk_length
    if not chunks or chunks[0][0] != CHUNK_JSON:
        _fail("the first chunk is not JSON (type 0x4E4F534A)")
    json_bytes = chunks[0][1]
    text = json_bytes.rstrip(b" ")
    if text.endswith(b"\x00"):
        _fail("the JSON chunk is padded with zeros, expected spaces (0x20)")
    try:
        gltf = json.loads(text.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as error:
        _fail(f"the JSON chunk does not parse: {error}")
    if not isinstance(gltf, dict):
        _fail("the JSON chunk is not an object")
    binary = None
    if len(chunks) > 1:
        if chunks[1][0] != CHUNK_BIN:
            _fail(f"the second chunk has type 0x{chunks[1][0]:08X}, expected BIN (0x004E4942)")
        binary = chunks[1][1]
    if len(chunks) > 2:
        _fail(f"{len(chunks)} chunks; limsurf writes JSON and BIN only")
    return gltf, binary, len(json_bytes), (len(binary) if binary is not None else 0)


def _get(items: list[Any], index: Any, what: str) -> Any:
    if not isinstance(index, int) or isinstance(index, bool) or not 0 <= index < len(items):
        _fail(f"{what} {index!r} does not exist ({len(items)} defined)")
    return items[index]


def _buffer_bytes(gltf: dict[str, Any], binary: bytes | None, index: int) -> bytes:
    buffer = _get(gltf.get("buffers", []), index, "buffer")
    if "uri" in buffer:
        _fail(f"buffer {index} has a uri; only the GLB's own buffer is read")
    if index != 0 or binary is None:
        _fail(f"buffer {index} has no BIN chunk to live in")
    declared = buffer.get("byteLength")
    if not isinstance(declared, int) or not len(binary) - 3 <= declared <= len(binary):
        _fail(f"buffer byteLength {declared!r} does not match the BIN chunk's {len(binary)} bytes")
    return binary[:declared]


def read_accessor(gltf: dict[str, Any], binary: bytes | None, index: int) -> np.ndarray:
    """Accessor @p index as an array of shape (count,) for SCALAR, (count, n) otherwise.

    Normalized integer accessors become float32 in [0, 1] (signed ones in [-1, 1]); min and
    max, when given, are checked against the stored values.
    """
    accessor = _get(gltf.get("accessors", []), index, "accessor")
    what = f"accessor {index}"
    if "sparse" in accessor:
        _fail(f"{what}: sparse accessors are not read")
    component_type = accessor.get("componentType")
    if component_type not in COMPONENT_DTYPES:
        _fail(f"{what}: unknown componentType {component_type!r}")
    kind = accessor.get("type")
    if kind not in TYPE_COMPONENTS:
        _fail(f"{what}: unknown type {kind!r}")
    if kind.startswith("MAT"):
        _fail(f"{what}: matrix accessors are not read")
    count = accessor.get("count")
    if not isinstance(count, int) or count < 1:
        _fail(f"{what}: count {count!r}, expected a positive integer")
    dtype = COMPONENT_DTYPES[component_type]
    n = TYPE_COMPONENTS[kind]
    element = dtype.itemsize * n
    if "bufferView" not in accessor:
        _fail(f"{what}: no bufferView (all-zero accessors are not read)")
    view = _get(gltf.get("bufferViews", []), accessor["bufferView"], "bufferView")
    data = _buffer_bytes(gltf, binary, view.get("buffer"))
    view_offset = view.get("byteOffset", 0)
    view_length = view.get("byteLength")
    if not isinstance(view_length, int) or view_length < 1 or view_offset < 0 or view_offset + view_length > len(data):
        _fail(f"bufferView {accessor['bufferView']}: bytes [{view_offset}, {view_offset}+{view_length}) "
              f"outside its buffer of {len(data)} bytes")
    target = view.get("target")
    if target is not None and target not in (ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER):
        _fail(f"bufferView {accessor['bufferView']}: target {target!r}, expected 34962 or 34963")
    stride = view.get("byteStride")
    if stride is not None and (not isinstance(stride, int) or stride < 4 or stride > 252 or stride % 4 != 0):
        _fail(f"bufferView {accessor['bufferView']}: byteStride {stride!r}, expected a multiple of 4 in [4, 252]")
    step = stride if stride is not None else element
    if step < element:
        _fail(f"{what}: byteStride {step} is smaller than an element ({element} bytes)")
    accessor_offset = accessor.get("byteOffset", 0)
    if accessor_offset % dtype.itemsize != 0 or (view_offset + accessor_offset) % dtype.itemsize != 0:
        _fail(f"{what}: offset {view_offset}+{accessor_offset} is not a multiple of the component size "
              f"{dtype.itemsize}")
    needed = accessor_offset + step * (count - 1) + element
    if needed > view_length:
        _fail(f"{what}: needs {needed} bytes of a bufferView of {view_length}")
    values = np.ndarray(shape=(count, n), dtype=dtype, buffer=data, offset=view_offset + accessor_offset,
                        strides=(step, dtype.itemsize)).copy()
    for bound, reduce in (("min", np.min), ("max", np.max)):
        if bound in accessor:
            declared = np.asarray(accessor[bound], dtype=np.float64)
            if declared.shape != (n,):
                _fail(f"{what}: {bound} has {declared.size} values, expected {n}")
            actual = reduce(values, axis=0)
            # JSON numbers compared as the stored type (a float written as its exact double).
            if not np.array_equal(declared.astype(dtype), actual):
                _fail(f"{what}: {bound} {declared.tolist()} is not the data's {actual.tolist()}")
    if accessor.get("normalized", False):
        if component_type in (FLOAT, UNSIGNED_INT):
            _fail(f"{what}: normalized is not allowed for componentType {component_type}")
        scale = float(np.iinfo(dtype).max)
        values = np.maximum(values.astype(np.float32) / np.float32(scale), np.float32(-1.0))
    return values[:, 0] if kind == "SCALAR" else values


def read_glb(source: str | os.PathLike[str] | bytes, *, mesh: int = 0, primitive: int = 0,
             normal_tolerance: float = 5e-4) -> GlbMesh:
    """Reads and checks a .glb file (a path or its bytes); returns one primitive, decoded."""
    if isinstance(source, (bytes, bytearray, memoryview)):
        data = bytes(source)
    else:
        with open(source, "rb") as file:
            data = file.read()
    gltf, binary, json_length, bin_length = _split_chunks(data)

    asset = gltf.get("asset")
    if not isinstance(asset, dict) or asset.get("version") != "2.0":
        _fail(f"asset.version is {asset.get('version') if isinstance(asset, dict) else None!r}, expected '2.0'")
    if gltf.get("extensionsRequired"):
        _fail(f"extensionsRequired {gltf['extensionsRequired']!r}: no extension is read")
    scenes = gltf.get("scenes", [])
    nodes = gltf.get("nodes", [])
    meshes = gltf.get("meshes", [])
    if "scene" in gltf:
        _get(scenes, gltf["scene"], "scene")
    for s, scene in enumerate(scenes):
        for node in scene.get("nodes", []):
            _get(nodes, node, f"scenes[{s}] node")
    for n, node in enumerate(nodes):
        if "mesh" in node:
            _get(meshes, node["mesh"], f"nodes[{n}] mesh")
    buffers = gltf.get("buffers", [])
    if binary is not None and (not buffers or "uri" in buffers[0]):
        _fail("a BIN chunk but no buffers[0] without uri to describe it")
    if buffers and "uri" not in buffers[0]:
        used = len(_buffer_bytes(gltf, binary, 0))
        if any(binary[used:]):
            _fail("the BIN chunk is padded with non-zero bytes")
    for v, view in enumerate(gltf.get("bufferViews", [])):
        if view.get("target") not in (None, ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER):
            _fail(f"bufferView {v}: target {view.get('target')!r}, expected 34962 or 34963")

    the_primitive = _get(_get(meshes, mesh, "mesh").get("primitives", []), primitive, f"meshes[{mesh}] primitive")
    mode = the_primitive.get("mode", MODE_TRIANGLES)
    if mode != MODE_TRIANGLES:
        _fail(f"primitive mode {mode!r}, expected 4 (TRIANGLES)")
    attributes_json = the_primitive.get("attributes", {})
    if "POSITION" not in attributes_json:
        _fail("the primitive has no POSITION")
    accessors = gltf.get("accessors", [])
    attributes: dict[str, np.ndarray] = {}
    names: dict[str, str | None] = {}
    count = None
    for name, index in attributes_json.items():
        accessor = _get(accessors, index, f"attribute {name}: accessor")
        component_type, kind = accessor.get("componentType"), accessor.get("type")
        standard = name in ("POSITION", "NORMAL", "TANGENT") or name.split("_")[0] in ("TEXCOORD", "COLOR", "JOINTS",
                                                                                       "WEIGHTS")
        if not standard and not name.startswith("_"):
            _fail(f"attribute {name}: application-specific names must start with '_'")
        if name.startswith("_") and component_type == UNSIGNED_INT:
            _fail(f"attribute {name}: application-specific attributes must not be UNSIGNED_INT")
        if name in ("POSITION", "NORMAL") and (component_type, kind) != (FLOAT, "VEC3"):
            _fail(f"attribute {name}: componentType {component_type} {kind}, expected FLOAT (5126) VEC3")
        if name == "POSITION" and ("min" not in accessor or "max" not in accessor):
            _fail("attribute POSITION: min and max are required")
        if name.startswith("COLOR_"):
            if kind not in ("VEC3", "VEC4"):
                _fail(f"attribute {name}: type {kind}, expected VEC3 or VEC4")
            if not (component_type == FLOAT or (component_type in (UNSIGNED_BYTE, UNSIGNED_SHORT)
                                                and accessor.get("normalized", False))):
                _fail(f"attribute {name}: expected FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT")
        view = _get(gltf.get("bufferViews", []), accessor.get("bufferView"), f"attribute {name}: bufferView")
        if view.get("target") not in (None, ARRAY_BUFFER):
            _fail(f"attribute {name}: bufferView target {view.get('target')}, expected 34962 (ARRAY_BUFFER)")
        element = COMPONENT_DTYPES.get(component_type, np.dtype("u1")).itemsize * TYPE_COMPONENTS.get(kind, 1)
        if (view.get("byteOffset", 0) + accessor.get("byteOffset", 0)) % 4 != 0 or \
                view.get("byteStride", element) % 4 != 0:
            _fail(f"attribute {name}: elements are not aligned to 4 bytes")
        values = read_accessor(gltf, binary, index)
        if count is not None and len(values) != count:
            _fail(f"attribute {name}: {len(values)} values, the other attributes have {count}")
        count = len(values)
        attributes[name] = values
        names[name] = accessor.get("name")

    normals = attributes.get("NORMAL")
    if normals is not None:
        lengths = np.linalg.norm(normals.astype(np.float64), axis=1)
        worst = int(np.argmax(np.abs(lengths - 1.0)))
        if abs(lengths[worst] - 1.0) > normal_tolerance:
            _fail(f"attribute NORMAL: vertex {worst} has length {lengths[worst]}, expected 1")
    colors = attributes.get("COLOR_0")
    if colors is not None and not (np.all(colors >= 0.0) and np.all(colors <= 1.0)):
        _fail("attribute COLOR_0: values outside [0, 1]")

    num_vertices = len(attributes["POSITION"])
    if "indices" in the_primitive:
        index = the_primitive["indices"]
        accessor = _get(accessors, index, "indices: accessor")
        if accessor.get("type") != "SCALAR" or accessor.get("componentType") not in (UNSIGNED_BYTE, UNSIGNED_SHORT,
                                                                                     UNSIGNED_INT):
            _fail("indices: expected SCALAR UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT")
        if accessor.get("normalized", False):
            _fail("indices: must not be normalized")
        view = _get(gltf.get("bufferViews", []), accessor.get("bufferView"), "indices: bufferView")
        if view.get("target") not in (None, ELEMENT_ARRAY_BUFFER):
            _fail(f"indices: bufferView target {view.get('target')}, expected 34963 (ELEMENT_ARRAY_BUFFER)")
        flat = read_accessor(gltf, binary, index).astype(np.uint32)
    else:
        flat = np.arange(num_vertices, dtype=np.uint32)
    if len(flat) % 3 != 0:
        _fail(f"indices: {len(flat)} of them, not a multiple of 3 for TRIANGLES")
    if len(flat) and int(flat.max()) >= num_vertices:
        _fail(f"indices: index {int(flat.max())} out of range [0, {num_vertices})")

    return GlbMesh(gltf=gltf, positions=attributes["POSITION"], triangles=flat.reshape(-1, 3), normals=normals,
                   colors=colors, attributes=attributes, accessor_names=names, header_length=len(data),
                   json_chunk_length=json_length, bin_chunk_length=bin_length)


def _main(argv: list[str]) -> int:
    if len(argv) != 2:
        print("usage: glb_reader.py FILE.glb", file=sys.stderr)
        return 2
    try:
        mesh = read_glb(argv[1])
    except (GlbError, OSError) as error:
        print(f"{argv[1]}: {error}", file=sys.stderr)
        return 1
    print(f"{argv[1]}: {len(mesh.positions)} vertices, {len(mesh.triangles)} triangles; "
          f"generator {mesh.gltf['asset'].get('generator')!r}")
    for name, values in mesh.attributes.items():
        print(f"  {name}: {values.dtype} {values.shape}, accessor name {mesh.accessor_names[name]!r}")
    return 0


if __name__ == "__main__":
    sys.exit(_main(sys.argv))
