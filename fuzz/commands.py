#!/usr/bin/env python3
"""Mutation fuzzing of the CLI's commands (docs/io.md "Fuzzing").

The libFuzzer targets beside this file feed bytes to the readers. This script feeds nearly valid
meshes to the commands, so that what runs after reading (validation, the schemes' refusals, the
limit basis, the solvers, the writers) sees bad input too: bundled meshes with a few lines
changed (odd numbers, bad indices, repeated or reversed faces, bad tags, truncation) run through
every command, and the PLY/OFF encodings of some of them with bytes changed run through the
readers' commands.

A finding is a signal or abort, a run over --timeout seconds, a failure with nothing on stderr, an
uncaught exception's text, a NaN or infinity printed by a run that succeeded, or an output file
left by a run that failed. Each is kept under --out with its input and command line.

    python3 fuzz/commands.py build/ci/cli/limsurf --iterations 3000 --seed 1
"""
import argparse
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MESHES = os.path.join(ROOT, "data", "meshes")
SEEDS = ["cube", "tetrahedron", "icosahedron", "quad_grid", "torus_4x5", "cube_creases", "plate_sym",
         "single_quad", "annulus", "disk_ev5_quads", "tri_grid", "pentagon", "cube_ngons", "octahedron",
         "tetra_1", "quad_valence_5", "rve_block", "hexagon_fan"]
ENCODED_SEEDS = ["cube", "icosahedron", "quad_grid", "torus_4x5", "tri_grid"]

# {m}: the input, {s}: the scheme, {w}: the output folder, {method}: dec, sec or iga.
COMMANDS = [
    ["info", "{m}", "--json"], ["convert", "{m}", "{w}/o.ply"], ["convert", "{m}", "{w}/o.off"],
    ["subdivide", "{m}", "--scheme", "{s}", "-o", "{w}/s.obj", "--levels", "2"],
    ["subdivide", "{m}", "--scheme", "{s}", "--boundary", "none", "-o", "{w}/s.obj"],
    ["eval", "{m}", "--scheme", "{s}", "--grid", "3", "--json"],
    ["measure", "{m}", "--scheme", "{s}", "--json"],
    ["measure", "{m}", "--scheme", "{s}", "--json", "--creasing", "chaikin", "--boundary", "none"],
    ["volume", "{m}", "--scheme", "{s}", "--json"],
    ["poisson", "{m}", "--scheme", "{s}", "--rhs", "x*y", "--method", "{method}", "--level", "2", "--json"],
    ["render", "{m}", "--scheme", "{s}", "-o", "{w}/r.png", "--size", "32x32", "--resolution", "2"],
    ["geodesic", "{m}", "--scheme", "{s}", "--source", "0", "--method", "{method}", "--level", "2", "--json"],
    ["hodge", "{m}", "--scheme", "{s}", "--random", "3", "--level", "2", "--json"],
    ["vector-field", "{m}", "--scheme", "{s}", "--source", "0:1", "--level", "2", "--json"],
    ["parameterize", "{m}", "--scheme", "{s}", "-o", "{w}/p.obj"],
    ["membrane", "{m}", "--scheme", "{s}", "--evaluate-only", "--json"],
    ["membrane", "{m}", "--scheme", "{s}", "--area", "12.566", "--reduced-volume", "0.9", "--max-iterations", "5",
     "--json", "-o", "{w}/mb.obj"],
    ["membrane", "{m}", "--scheme", "{s}", "--area", "12.566", "--reduced-volume", "0.7", "--max-iterations", "3",
     "--continuation", "2", "--json", "-o", "{w}/mb.obj"],
    ["plate", "{m}", "--json"], ["shell", "{m}", "--scheme", "{s}", "--pressure", "1", "--json"],
    ["elasticity", "{m}", "--json"], ["reverse", "{m}", "-o", "{w}/rv.obj"],
]
ENCODED_COMMANDS = [["info", "{m}", "--json"], ["convert", "{m}", "{w}/o.obj"],
                    ["measure", "{m}", "--scheme", "{s}", "--json"],
                    ["subdivide", "{m}", "--scheme", "{s}", "-o", "{w}/s.ply"]]
OUTPUTS = ["o.ply", "o.off", "o.obj", "s.obj", "s.ply", "r.png", "p.obj", "mb.obj", "rv.obj"]

ODD_NUMBERS = ["nan", "inf", "-inf", "1e308", "-1e308", "1e-320", "0", "-0", "1e400", "0x1p3", "", "abc", "1.5.5",
               "+", "3e", "99999999999999999999"]
ODD_INDICES = ["0", "-1", "-999", "1/2/3", "1//", "/", "2147483648", "-2147483649"]
ODD_LINES = ["t crease 2/1 0 1/5", "t crease 2/1 1 2/nan", "t corner 1/1 0/-3", "t interpolateboundary 1/0 0",
             "t interpolateboundary 1/0 9", "t crease 2/1 0 0/2", "t crease 2/1 0 99/1", "t crease 2/1 0 1/inf",
             "t foo 0/0/0", "t crease 1/1 0/1", "t corner 1/1 9999/1", "g x", "s off", "mtllib x.mtl", "vn 0 0 1",
             "vt 0 0", "l 1 2", "p 1", "f", "v", "v 1 2", "v 1 2 3 4 5", "f 1 1 1", "f 1 2", "#\x00", "\t",
             "v 1e308 1e308 1e308"]
PLY_HEADER_LINES = [b"property list uchar int vertex_indices", b"property list int int vertex_indices",
                    b"property list uchar uint vertex_indices", b"property list char int vertex_indices",
                    b"property float x", b"property double nx", b"element vertex 99999999999", b"element vertex -1",
                    b"element face 0", b"element face 4294967296", b"element vertex 2",
                    b"format binary_little_endian 1.0", b"format binary_big_endian 1.0", b"format ascii 1.0",
                    b"property list uchar double vertex_indices", b"element edge 3", b"property uchar red",
                    b"comment x", b"end_header", b""]


def mutate_obj(lines, rng):
    """A few of the line-level changes a broken exporter or a hand edit makes."""
    lines = list(lines)
    for _ in range(rng.randint(1, 4)):
        if not lines:
            lines.append("v 0 0 0")
            continue
        i = rng.randrange(len(lines))
        words = lines[i].split()
        kind = rng.randrange(14)
        face = bool(words) and words[0] == "f"
        if kind == 0:
            del lines[i]
        elif kind == 1:
            lines.insert(rng.randrange(len(lines) + 1), lines[i])
        elif kind == 2 and words and words[0] == "v" and len(words) > 1:
            words[rng.randrange(1, len(words))] = rng.choice(ODD_NUMBERS)
            lines[i] = " ".join(words)
        elif kind == 3 and face and len(words) > 1:
            words[rng.randrange(1, len(words))] = rng.choice(
                ODD_INDICES + [str(rng.randint(1, 60)), words[rng.randrange(1, len(words))]])
            lines[i] = " ".join(words)
        elif kind == 4 and face and len(words) > 2:
            del words[rng.randrange(1, len(words))]
            lines[i] = " ".join(words)
        elif kind == 5 and face:
            words.append(words[rng.randrange(1, len(words))] if len(words) > 1 else "1")
            lines[i] = " ".join(words)
        elif kind == 6 and face and len(words) > 2:
            lines[i] = " ".join(words[:1] + words[:0:-1])
        elif kind == 7:
            lines.insert(i, rng.choice(ODD_LINES))
        elif kind == 8:
            lines[i] = lines[i][:rng.randrange(len(lines[i]) + 1)]
        elif kind == 9:
            lines.insert(i, "f " + " ".join(str(rng.randint(1, 12)) for _ in range(rng.randint(3, 9))))
        elif kind == 10 and words and words[0] == "v":
            lines[i] = "v " + " ".join(str(rng.uniform(-1, 1) * 10 ** rng.randint(-200, 200)) for _ in range(3))
        elif kind == 11:
            lines = lines[:rng.randrange(len(lines) + 1)]
        elif kind == 12:  # two vertices at one place
            vertices = [j for j, line in enumerate(lines) if line.startswith("v ")]
            if len(vertices) > 1:
                a, b = rng.sample(vertices, 2)
                lines[a] = lines[b]
        elif kind == 13:  # a face repeated, reversed
            faces = [j for j, line in enumerate(lines) if line.startswith("f ")]
            if faces:
                words = lines[rng.choice(faces)].split()
                lines.append("f " + " ".join(reversed(words[1:])))
    return "\n".join(lines)


def mutate_bytes(data, rng):
    """Byte-level changes of an encoded file, and header lines replaced or inserted."""
    data = bytearray(data)
    for _ in range(rng.randint(1, 5)):
        if not data:
            data += b"ply\n"
            continue
        i = rng.randrange(len(data))
        kind = rng.randrange(8)
        if kind == 0:
            data[i] = rng.randrange(256)
        elif kind == 1:
            del data[i:i + rng.randint(1, 16)]
        elif kind == 2:
            del data[i:]
        elif kind == 3:
            data[i:i] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 16)))
        elif kind == 4 and b"end_header" in data:
            end = data.index(b"end_header")
            header = bytes(data[:end]).split(b"\n")
            j = rng.randrange(len(header))
            if rng.random() < 0.5:
                header[j] = rng.choice(PLY_HEADER_LINES)
            else:
                header.insert(j, rng.choice(PLY_HEADER_LINES))
            data = bytearray(b"\n".join(header)) + data[end:]
        elif kind == 5:
            words = bytes(data).split(b" ")
            words[rng.randrange(len(words))] = rng.choice(
                [b"nan", b"-1", b"0", b"99999", b"4294967295", b"1e999", b"x", b"3\n", b"255"])
            data = bytearray(b" ".join(words))
        elif kind == 6 and len(data) > 4:
            j = rng.randrange(len(data) - 4)
            data[j:j + 4] = rng.choice([b"\xff\xff\xff\xff", b"\x00\x00\x00\x80", b"\x7f\xff\xff\xff", b"\x00\x01\x00\x00"])
        elif kind == 7:
            data[i:i] = data[max(0, i - 40):i]
    return bytes(data)


def finding(rc, stdout, stderr, command, work):
    if rc is None:
        return "hang"
    if rc < 0 or rc >= 128:
        return "crash"
    if rc != 0 and not stderr.strip():
        return "silent"
    if rc != 0 and ("terminate called" in stderr or "what():" in stderr):
        return "uncaught"
    if rc == 0 and re.search(r"\b(nan|inf)\b", stdout.lower()) and "nan" not in " ".join(command):
        return "nan"
    if rc != 0 and any(os.path.exists(os.path.join(work, name)) for name in OUTPUTS):
        return "half-written"
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("cli", help="the limsurf executable")
    parser.add_argument("--iterations", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--timeout", type=float, default=30.0, help="seconds before a run counts as a hang")
    parser.add_argument("--out", default="fuzz-findings", help="where findings are kept")
    args = parser.parse_args()
    rng = random.Random(args.seed)
    work = tempfile.mkdtemp(prefix="limsurf-fuzz-")
    encoded = []
    for name in ENCODED_SEEDS:  # the PLY (three encodings) and OFF forms of some seeds
        for suffix, extra in [(".off", []), (".ply", []), ("_le.ply", ["--ply-encoding", "binary-le"]),
                              ("_be.ply", ["--ply-encoding", "binary-be"])]:
            path = os.path.join(work, "seed_" + name + suffix)
            subprocess.run([args.cli, "convert", os.path.join(MESHES, name + ".obj"), path] + extra,
                           capture_output=True, check=True)
            encoded.append(path)
    counts = {}
    for iteration in range(args.iterations):
        for name in os.listdir(work):
            if not name.startswith("seed_"):
                os.remove(os.path.join(work, name))
        if rng.random() < 0.8:
            seed = rng.choice(SEEDS)
            text = mutate_obj(open(os.path.join(MESHES, seed + ".obj")).read().split("\n"), rng)
            mesh = os.path.join(work, "mesh.obj")
            with open(mesh, "w") as f:
                f.write(text)
            triangles = any(len(line.split()) == 4 for line in text.split("\n") if line.startswith("f "))
            command = rng.choice(COMMANDS)
        else:
            seed = rng.choice(encoded)
            mesh = os.path.join(work, "mesh" + os.path.splitext(seed)[1])
            with open(mesh, "wb") as f:
                f.write(mutate_bytes(open(seed, "rb").read(), rng))
            triangles = "icosahedron" in seed or "tri_" in seed
            command = rng.choice(ENCODED_COMMANDS)
        schemes = ["loop", "catmull-clark", "doo-sabin", "c2g0"] if rng.random() < 0.3 else \
            ["loop" if triangles else "catmull-clark"]
        command = [word.format(m=mesh, s=rng.choice(schemes), w=work, method=rng.choice(["dec", "sec", "iga"]))
                   for word in command]
        try:
            run = subprocess.run([args.cli] + command, capture_output=True, timeout=args.timeout, text=True,
                                 errors="replace")
            rc, stdout, stderr = run.returncode, run.stdout, run.stderr
        except subprocess.TimeoutExpired:
            rc, stdout, stderr = None, "", ""
        kind = finding(rc, stdout, stderr, command, work)
        if kind:
            counts[kind] = counts.get(kind, 0) + 1
            keep = os.path.join(args.out, "%s_%d_%d" % (kind, args.seed, iteration))
            os.makedirs(keep, exist_ok=True)
            shutil.copy(mesh, keep)
            with open(os.path.join(keep, "command.txt"), "w") as f:
                f.write(" ".join(command) + "\n" + kind + "\n--- stderr\n" + stderr[-4000:] + "\n--- stdout\n" +
                        stdout[-4000:])
            print(kind, command[0], keep, flush=True)
    shutil.rmtree(work)
    print("%d runs, findings: %s" % (args.iterations, counts or "none"))
    return 1 if counts else 0


if __name__ == "__main__":
    sys.exit(main())
