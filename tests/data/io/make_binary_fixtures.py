#!/usr/bin/env python3
"""Writes the binary PLY fixtures of tests/data/io and tests/data/malformed.

Run from this directory: python3 make_binary_fixtures.py
The files are committed; this script documents how they were made.
"""
import struct
from pathlib import Path

HERE = Path(__file__).resolve().parent
MALFORMED = HERE.parent / "malformed"

# A unit square split into two triangles, plus a fifth vertex on top: a pyramid-ish fan.
POSITIONS = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0), (0.5, 0.5, 0.75)]
FACES = [(0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4), (0, 3, 2, 1)]


def extra_props(order: str) -> bytes:
    """Mixed types, an element before 'vertex', lists in every element, one after 'face'."""
    header = (
        "ply\n"
        f"format {'binary_little_endian' if order == '<' else 'binary_big_endian'} 1.0\n"
        "comment hand-made fixture: extra elements and properties of every kind\n"
        "element material 2\n"
        "property list uchar short ids\n"
        "property double shininess\n"
        "element vertex 5\n"
        "property float x\n"
        "property uchar red\n"
        "property double y\n"
        "property list int uint16 neighbours\n"
        "property int16 z_scaled\n"
        "property float32 z\n"
        "property int8 flag\n"
        "element face 5\n"
        "property uint8 kind\n"
        "property list uchar int vertex_indices\n"
        "property list ushort float uv\n"
        "element edge 1\n"
        "property uint v1\n"
        "property uint v2\n"
        "end_header\n"
    ).encode()
    body = b""
    body += struct.pack(order + "B3hd", 3, 1, 2, 3, 0.5)
    body += struct.pack(order + "Bd", 0, 1.5)
    for i, (x, y, z) in enumerate(POSITIONS):
        neighbours = list(range(i))
        body += struct.pack(order + "fBdi", x, 200 + i, y, len(neighbours))
        body += struct.pack(order + f"{len(neighbours)}H", *neighbours)
        body += struct.pack(order + "hfb", -7, z, -1)
    for f, face in enumerate(FACES):
        body += struct.pack(order + f"BB{len(face)}i", f, len(face), *face)
        body += struct.pack(order + "H2f", 2, 0.25, 0.75)
    body += struct.pack(order + "II", 0, 1)
    return header + body


def main() -> None:
    (HERE / "extra_props_le.ply").write_bytes(extra_props("<"))
    (HERE / "extra_props_be.ply").write_bytes(extra_props(">"))

    # Truncated: the data stops inside face 1 (fixed-size data that is too short is caught
    # earlier, by the size check on the element counts).
    header = (
        b"ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
        b"property float x\nproperty float y\nproperty float z\n"
        b"element face 2\nproperty list uchar int vertex_indices\nend_header\n"
    )
    data = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    data += struct.pack("<B3i", 3, 0, 1, 2) + struct.pack("<Bi", 3, 0)
    (MALFORMED / "parse_truncated_binary.ply").write_bytes(header + data)

    # An absurd count in a tiny file: must be refused before any allocation.
    header = (
        b"ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\n"
        b"property float x\nproperty float y\nproperty float z\nend_header\n"
    )
    (MALFORMED / "parse_absurd_count.ply").write_bytes(header + bytes(20))

    # A face index beyond the vertices, in binary big-endian data.
    header = (
        b"ply\nformat binary_big_endian 1.0\nelement vertex 3\n"
        b"property double x\nproperty double y\nproperty double z\n"
        b"element face 2\nproperty list uchar int vertex_indices\nend_header\n"
    )
    data = struct.pack(">9d", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    data += struct.pack(">B3i", 3, 0, 1, 2) + struct.pack(">B3i", 3, 0, 2, 7)
    (MALFORMED / "parse_binary_index_out_of_range.ply").write_bytes(header + data)


if __name__ == "__main__":
    main()
