#!/usr/bin/env python3
"""Replays adversarial inputs through every limsurf command and checks the CLI's promise.

For each input (the committed corpus in tests/data/malformed and tests/cli/adversarial/corpus,
plus inputs generated here: huge faces and valences, scaled and flattened meshes, byte-order
marks, CR line endings, special files) and each command, and for the commands that read no mesh
(tune) once each with bad options, and every number option of every command with values at the
edges of a double (option_cases), a run must:
  - end within its time bound (no hang), with exit code 0, 1 or 2 (never 3, never a signal);
  - on failure, print exactly one "error: " line on stderr (as its last line), at most
    max_warning_lines warnings, and leave no output file and no temporary file;
  - on success, print no nan or inf anywhere (stdout, output files), and write output meshes
    that limsurf reads back.
Runs whose inputs are huge (10^5 corners or edges) must also finish, accepted or refused, within
a second. The last line is "N passed, M failed".

Usage: replay.py LIMSURF REPO_ROOT WORK_DIR [--huge N] [--time-scale F] [--inputs DIR]

With --inputs DIR, the meshes of DIR (every .obj, .off and .ply) go through every command instead,
nothing else: e.g. --inputs tests/data/opensubdiv_shapes (122 shapes, about 5 minutes on 2 cores;
run by hand, not by the suite).
"""
import argparse
import concurrent.futures
import math
import os
import re
import shutil
import subprocess
import sys
import threading
import time

MAX_WARNING_LINES = 11  # cli/output.h: 10 warnings and one "… and N more" line
NON_FINITE = re.compile(r"(?<![A-Za-z_])[-+]?(nan|inf|infinity)(?![A-Za-z_])", re.IGNORECASE)
SLOW_SECONDS = 60.0  # any run: a hang is far beyond this
HUGE_SECONDS = 1.0  # runs on the huge generated inputs


# ---------------------------------------------------------------------------- inputs

def polygon(n, z=0.0, scale=1.0):
    return ["v %r %r %r" % (scale * math.cos(2 * math.pi * i / n), scale * math.sin(2 * math.pi * i / n), z)
            for i in range(n)]


def write(path, lines, newline="\n", prefix=b""):
    with open(path, "wb") as f:
        f.write(prefix + (newline.join(lines) + newline).encode())
    return path


def cube_lines(scale=1.0, flat=False):
    corners = [(x, y, z) for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)]
    lines = ["v %r %r %r" % (scale * x, scale * y, 0.0 if flat else scale * z) for x, y, z in corners]
    return lines + ["f 5 7 8 6", "f 1 2 4 3", "f 3 4 8 7", "f 1 5 6 2", "f 2 6 8 4", "f 1 3 7 5"]


def generate(work, corners):
    """Writes the generated inputs; returns {name: (path, is_huge)}. The huge ones have about
    @p corners face corners each, in one face (disk), two (pillow), or around one vertex (fan)
    or two (bipyramid)."""
    out = {}
    n = corners
    out["disk"] = (write(os.path.join(work, "disk.obj"), polygon(n) + ["f " + " ".join(map(str, range(1, n + 1)))]),
                   True)
    n = corners // 2
    out["pillow"] = (write(os.path.join(work, "pillow.obj"),
                           polygon(n) + ["f " + " ".join(map(str, range(1, n + 1))),
                                         "f " + " ".join(map(str, range(n, 0, -1)))]), True)
    # A cone whose apex has valence n, closed by a bipyramid's second apex.
    n = corners // 6
    ring = polygon(n)
    faces = ["f 1 %d %d" % (i + 3, (i + 1) % n + 3) for i in range(n)]
    faces += ["f 2 %d %d" % ((i + 1) % n + 3, i + 3) for i in range(n)]
    out["bipyramid"] = (write(os.path.join(work, "bipyramid.obj"), ["v 0 0 1", "v 0 0 -1"] + ring + faces), True)
    n = corners // 3
    ring = polygon(n)
    fan = ["f 1 %d %d" % (i + 2, (i + 1) % n + 2) for i in range(n)]
    out["fan"] = (write(os.path.join(work, "fan.obj"), ["v 0 0 1"] + ring + fan), True)
    for name, scale in [("cube_1e-160", 1e-160), ("cube_1e-100", 1e-100), ("cube_1e80", 1e80),
                        ("cube_1e155", 1e155), ("cube_1.7e308", 1.7e308)]:
        out[name] = (write(os.path.join(work, name + ".obj"), cube_lines(scale)), False)
    out["cube_flat"] = (write(os.path.join(work, "cube_flat.obj"), cube_lines(flat=True)), False)
    bom = b"\xef\xbb\xbf"
    out["bom_obj"] = (write(os.path.join(work, "bom.obj"), cube_lines(), prefix=bom), False)
    out["bom_off"] = (write(os.path.join(work, "bom.off"),
                            ["OFF", "4 4 0", "0 0 0", "1 0 0", "0 1 0", "0 0 1",
                             "3 0 2 1", "3 0 1 3", "3 0 3 2", "3 1 2 3"], prefix=bom), False)
    out["bom_ply"] = (write(os.path.join(work, "bom.ply"),
                            ["ply", "format ascii 1.0", "element vertex 4", "property float x",
                             "property float y", "property float z", "element face 4",
                             "property list uchar int vertex_indices", "end_header", "0 0 0", "1 0 0", "0 1 0",
                             "0 0 1", "3 0 2 1", "3 0 1 3", "3 0 3 2", "3 1 2 3"], prefix=bom), False)
    out["cr_obj"] = (write(os.path.join(work, "cr.obj"), cube_lines(), newline="\r"), False)
    out["cr_off"] = (write(os.path.join(work, "cr.off"),
                           ["OFF", "4 4 0", "0 0 0", "1 0 0", "0 1 0", "0 0 1",
                            "3 0 2 1", "3 0 1 3", "3 0 3 2", "3 1 2 3"], newline="\r"), False)
    out["cr_ply"] = (write(os.path.join(work, "cr.ply"),
                           ["ply", "format ascii 1.0", "element vertex 1", "property float x",
                            "property float y", "property float z", "end_header", "0 0 0"], newline="\r"), False)
    directory = os.path.join(work, "a_directory.obj")
    os.makedirs(directory, exist_ok=True)
    out["directory"] = (directory, False)
    return out


def corpus(root):
    out = {}
    for folder in [os.path.join(root, "tests", "data", "malformed"),
                   os.path.join(root, "tests", "cli", "adversarial", "corpus")]:
        if not os.path.isdir(folder):
            continue
        for name in sorted(os.listdir(folder)):
            out[name] = (os.path.join(folder, name), False)
    for name in ["cube.obj", "genus2.obj", "icosahedron.obj", "quad_grid.obj", "cube_creases.obj"]:
        out["bundled_" + name] = (os.path.join(root, "data", "meshes", name), False)
    return out


# ---------------------------------------------------------------------------- commands

def commands(mesh, out_dir, is_huge):
    """(label, argv, output files it may write) for one input."""
    def o(name):
        return os.path.join(out_dir, name)
    runs = [
        ("info", ["info", mesh], []),
        ("info --json", ["info", "--json", mesh], []),
        ("convert obj", ["convert", mesh, o("c.obj")], [o("c.obj")]),
        ("convert ply", ["convert", mesh, o("c.ply"), "--ply-encoding", "binary-le"], [o("c.ply")]),
        ("subdivide bilinear", ["subdivide", mesh, "--scheme", "bilinear", "--levels", "1", "-o", o("b.obj")],
         [o("b.obj")]),
        ("subdivide catmull-clark", ["subdivide", mesh, "--scheme", "catmull-clark", "--levels", "1", "-o", o("s.off")],
         [o("s.off")]),
        ("subdivide loop", ["subdivide", mesh, "--scheme", "loop", "--levels", "1", "-o", o("l.obj")], [o("l.obj")]),
        ("subdivide doo-sabin", ["subdivide", mesh, "--scheme", "doo-sabin", "--levels", "1", "-o", o("d.ply")],
         [o("d.ply")]),
        ("subdivide c2g0", ["subdivide", mesh, "--scheme", "c2g0", "--levels", "1", "-o", o("g.obj")], [o("g.obj")]),
        # Reverse Catmull-Clark: almost every input here is not a subdivided topology (refused naming it).
        ("reverse json", ["reverse", mesh, "-o", o("rv.obj"), "--json"], [o("rv.obj")]),
    ]
    if is_huge:
        return runs + [
            ("eval catmull-clark", ["eval", mesh, "--scheme", "catmull-clark", "--grid", "1"], []),
            ("volume doo-sabin", ["volume", mesh, "--scheme", "doo-sabin"], []),
            ("volume loop", ["volume", mesh, "--scheme", "loop"], []),
            ("poisson loop sec", ["poisson", mesh, "--scheme", "loop", "--rhs", "x"], []),
        ]
    return runs + [
        ("subdivide 2 levels", ["subdivide", mesh, "--scheme", "catmull-clark", "--levels", "2", "-o", o("s2.obj"),
                                "--json"], [o("s2.obj")]),
        ("eval catmull-clark", ["eval", mesh, "--scheme", "catmull-clark", "--grid", "2"], []),
        ("eval loop json", ["eval", mesh, "--scheme", "loop", "--grid", "2", "--json"], []),
        ("eval c2g0", ["eval", mesh, "--scheme", "c2g0", "--grid", "1", "--json"], []),
        ("eval doo-sabin to file", ["eval", mesh, "--scheme", "doo-sabin", "--grid", "1", "-o", o("e.json")],
         [o("e.json")]),
        ("measure catmull-clark", ["measure", mesh, "--scheme", "catmull-clark", "--degree", "6", "--tiles", "4"], []),
        ("measure loop json", ["measure", mesh, "--scheme", "loop", "--degree", "6", "--tiles", "4", "--json"], []),
        ("volume catmull-clark", ["volume", mesh, "--scheme", "catmull-clark", "--levels", "2"], []),
        ("volume doo-sabin json", ["volume", mesh, "--scheme", "doo-sabin", "--levels", "1", "--json"], []),
        ("volume loop moments", ["volume", mesh, "--scheme", "loop", "--levels", "1", "--moments", "--degree", "6",
                                 "--tiles", "4"], []),
        ("poisson catmull-clark sec", ["poisson", mesh, "--scheme", "catmull-clark", "--rhs", "x", "--level", "2",
                                       "-o", o("p.vtk")], [o("p.vtk")]),
        ("poisson loop dec json", ["poisson", mesh, "--scheme", "loop", "--method", "dec", "--rhs", "1e308*(x+0.6)",
                                   "--json"], []),
        ("poisson catmull-clark huge boundary", ["poisson", mesh, "--scheme", "catmull-clark", "--method", "dec",
                                                 "--rhs", "1", "--boundary-value", "1e308", "-o", o("q.vtu")],
         [o("q.vtu")]),
        ("plate", ["plate", mesh, "--json", "-o", o("w.vtk")], [o("w.vtk")]),
        ("shell free pressure", ["shell", mesh, "--pressure", "1e300", "--interpolate", "-o", o("u.vtk")],
         [o("u.vtk")]),
        ("render", ["render", mesh, "--scheme", "catmull-clark", "--field", "mean-curvature", "--size", "64x48",
                    "-o", o("r.png")], [o("r.png")]),
        ("parameterize sec", ["parameterize", mesh, "--scheme", "catmull-clark", "--level", "1", "--degree", "4",
                              "--tiles", "1", "-o", o("uv.obj")], [o("uv.obj")]),
        ("parameterize circle json", ["parameterize", mesh, "--scheme", "loop", "--method", "dec", "--boundary",
                                      "circle", "--degree", "4", "--tiles", "1", "--json"], []),
        ("geodesic sec", ["geodesic", mesh, "--scheme", "catmull-clark", "--source", "0", "--level", "1",
                          "-o", o("g.vtk")], [o("g.vtk")]),
        ("geodesic loop dec json", ["geodesic", mesh, "--scheme", "loop", "--source", "0", "--method", "dec",
                                    "--json"], []),
        ("vector-field", ["vector-field", mesh, "--scheme", "catmull-clark", "--method", "dec", "--vorticity", "0:1",
                          "--sample-level", "1", "-o", o("v.vtk")], [o("v.vtk")]),
        ("hodge json", ["hodge", mesh, "--scheme", "loop", "--method", "dec", "--random", "1", "--json"], []),
        ("membrane evaluate json", ["membrane", mesh, "--scheme", "loop", "--evaluate-only", "--json"], []),
        ("membrane canham", ["membrane", mesh, "--scheme", "catmull-clark", "--area", "1", "--reduced-volume", "0.9",
                             "--max-iterations", "5", "--degree", "4", "-o", o("m.obj"), "--field-output", o("m.vtk"),
                             "--resolution", "2"], [o("m.obj"), o("m.vtk")]),
        ("elasticity", ["elasticity", mesh, "--levels", "1", "--json", "-o", o("el.vtk"), "--png", o("el.png"),
                        "--size", "64x48", "--resolution", "2"], [o("el.vtk"), o("el.png")]),
        ("elasticity affine plane stress", ["elasticity", mesh, "--boundary", "affine", "--plane-stress",
                                            "--no-stiffness", "--macro-strain", "1e300,0;0,1"], []),
    ]


def standalone(out_dir):
    """(label, argv, output files it may write) for the commands that read no mesh, run once each:
    tune's refusals (valence 4, out-of-range valences and lambdas, malformed ranges, too few samples,
    options out of range, an unwritable curve) and two quick runs that succeed."""
    def o(name):
        return os.path.join(out_dir, name)
    tune = ["tune", "--valence"]
    return [
        ("tune valence 4", tune + ["4"], []),
        ("tune valence 4 at lambda", tune + ["4", "--lambda", "0.55"], []),
        ("tune valence 2", tune + ["2"], []),
        ("tune valence -1", tune + ["-1"], []),
        ("tune valence 129", tune + ["129", "--lambda", "0.6"], []),
        ("tune valence 2^31", tune + ["2147483648"], []),
        ("tune valence text", tune + ["five"], []),
        ("tune lambda above", tune + ["5", "--lambda", "0.9"], []),
        ("tune lambda below", tune + ["5", "--lambda", "0.1"], []),
        ("tune lambda nan", tune + ["5", "--lambda", "nan"], []),
        ("tune lambda inf", tune + ["5", "--lambda", "inf"], []),
        ("tune lambda 1e400", tune + ["5", "--lambda", "1e400"], []),
        ("tune range reversed", tune + ["5", "--lambda-range", "0.6,0.5"], []),
        ("tune range empty", tune + ["5", "--lambda-range", "0.5,0.5"], []),
        ("tune range one value", tune + ["5", "--lambda-range", "0.5"], []),
        ("tune range three values", tune + ["5", "--lambda-range", "0.4,0.5,0.6"], []),
        ("tune range nan", tune + ["5", "--lambda-range", "nan,0.6"], []),
        ("tune range outside", tune + ["5", "--lambda-range", "0.1,0.6"], []),
        ("tune samples 2", tune + ["5", "--samples", "2", "--curve", o("t.csv")], [o("t.csv")]),
        ("tune samples huge", tune + ["5", "--samples", "1000000000"], []),
        ("tune quadrature 0", tune + ["5", "--quadrature", "0"], []),
        ("tune quadrature 11", tune + ["5", "--lambda", "0.55", "--quadrature", "11"], []),
        ("tune tile levels -1", tune + ["5", "--tile-levels", "-1"], []),
        ("tune tile levels 21", tune + ["5", "--lambda", "0.55", "--tile-levels", "21"], []),
        ("tune poisson nan", tune + ["5", "--lambda", "0.55", "--poisson-ratio", "nan"], []),
        ("tune poisson -1", tune + ["5", "--lambda", "0.55", "--poisson-ratio", "-1"], []),
        ("tune shape", tune + ["5", "--shape", "bowl"], []),
        ("tune lambda with search options", tune + ["5", "--lambda", "0.55", "--samples", "5"], []),
        ("tune curve into a directory", tune + ["5", "--samples", "3", "--quadrature", "1", "--tile-levels", "2",
                                                "--curve", out_dir], []),
        ("tune curve in a missing folder", tune + ["5", "--samples", "3", "--quadrature", "1", "--tile-levels", "2",
                                                   "--curve", o("missing/t.csv")], []),
        ("tune at lambda", tune + ["7", "--lambda", "0.6", "--json"], []),
        ("tune search and curve", tune + ["3", "--shape", "saddle", "--samples", "5", "--quadrature", "2",
                                          "--tile-levels", "4", "--curve", o("t.csv"), "--json"], [o("t.csv")]),
    ]


def elasticity_cases(root, work, out_dir):
    """(label, argv, output files it may write) for `limsurf elasticity` on the bundled cells: bad
    materials, matrices, sides and files (refused), a failed second output (no file left), and runs
    that succeed."""
    def o(name):
        return os.path.join(out_dir, name)
    block = os.path.join(root, "data", "meshes", "rve_block.obj")
    inclusion = os.path.join(root, "data", "meshes", "square_inclusion.obj")
    # A 3 x 3 grid whose right side's middle vertices sit off the left side's heights.
    grid = ["v %d %r 0" % (i, 2.0 * j / 3 + (0.1 if i == 3 and 0 < j < 3 else 0.0))
            for j in range(4) for i in range(4)]
    grid += ["f %d %d %d %d" % (4 * j + i + 1, 4 * j + i + 2, 4 * j + i + 6, 4 * j + i + 5)
             for j in range(3) for i in range(3)]
    unmatched = write(os.path.join(work, "unmatched_sides.obj"), grid)
    few = write(os.path.join(work, "few_materials.txt"), ["0", "1", "1"])
    e = ["elasticity", block]
    return [
        ("elasticity nu 0.5", e + ["--nu", "0.5"], []),
        ("elasticity nu nan", e + ["--nu", "nan"], []),
        ("elasticity E 0", e + ["--E", "0"], []),
        ("elasticity E -1", e + ["--E", "-1"], []),
        ("elasticity E 1e400", e + ["--E", "1e400"], []),
        ("elasticity matrix short", e + ["--macro-strain", "1,0;0"], []),
        ("elasticity matrix words", e + ["--macro-strain", "a,b;c,d"], []),
        ("elasticity matrix three rows", e + ["--macro-strain", "1,0;0,1;1,1"], []),
        ("elasticity matrix nan", e + ["--macro-deformation", "nan,0;0,1"], []),
        ("elasticity matrix huge", e + ["--macro-strain", "1e308,1e308;1e308,1e308"], []),
        ("elasticity material unknown group", e + ["--material", "stone:2,0.3"], []),
        ("elasticity material one number", e + ["--material", "grain:2"], []),
        ("elasticity material nu 0.5", e + ["--material", "grain:2,0.5"], []),
        ("elasticity material twice", e + ["--material", "grain:2,0.3", "--material", "grain:3,0.3"], []),
        ("elasticity face materials missing", e + ["--face-materials", o("missing.txt"), "--material", "1:2,0.3"],
         []),
        ("elasticity face materials too few", e + ["--face-materials", few, "--material", "1:2,0.3"], []),
        ("elasticity face materials a mesh", e + ["--face-materials", block, "--material", "1:2,0.3"], []),
        ("elasticity loaded without clamp", e + ["--boundary", "loaded"], []),
        ("elasticity clamp when periodic", e + ["--clamp", "left"], []),
        ("elasticity clamp middle", e + ["--boundary", "loaded", "--clamp", "middle"], []),
        ("elasticity traction malformed", e + ["--boundary", "loaded", "--clamp", "left", "--traction", "right:1"],
         []),
        ("elasticity body force malformed", e + ["--body-force", "1"], []),
        ("elasticity periodic contradicts", e + ["--periodic", "--boundary", "affine"], []),
        ("elasticity levels 7", e + ["--levels", "7"], []),
        ("elasticity quadrature 0", e + ["--quadrature", "0"], []),
        ("elasticity output obj", e + ["-o", o("el.obj")], []),
        ("elasticity png jpg", e + ["--png", o("el.jpg")], []),
        ("elasticity output over input", e + ["-o", block], []),
        ("elasticity png in a missing folder", e + ["-o", o("el.vtk"), "--png", o("missing/el.png"),
                                                    "--resolution", "1", "--size", "32x32"], []),
        ("elasticity unmatched sides", ["elasticity", unmatched], []),
        ("elasticity grains", e + ["--material", "grain:10,0.3", "--levels", "1", "--json", "-o", o("el.vtu"),
                                   "--png", o("el.png"), "--png-field", "von-mises", "--size", "64x48"],
         [o("el.vtu"), o("el.png")]),
        ("elasticity inclusion plane stress affine", ["elasticity", inclusion, "--material", "inclusion:10,0.2",
                                                      "--plane-stress", "--boundary", "affine", "--json"], []),
        ("elasticity loaded", e + ["--boundary", "loaded", "--clamp", "left", "--clamp", "bottom", "--traction",
                                   "right:1,0.5", "--body-force", "0,-1", "-o", o("el.vtk")], [o("el.vtk")]),
    ]


# ---------------------------------------------------------------------------- checks

# Every number option of every command, one at a time, with values at the edges of a double (a sweep
# of this kind, 2026-12-06, found a crash inside Ipopt on a subnormal target, a device replaced by a
# regular file, outputs left behind, and 0/0 reported as an overflow). Each entry: a valid run on a
# bundled mesh, the options to vary, and the outputs it may write.
HOSTILE_NUMBERS = ["nan", "-inf", "-1", "0", "1e-320", "1e308"]


def option_cases(root, out_dir):
    """(label, argv, output files it may write): each command's number options given hostile values,
    and its outputs in a missing folder."""
    def mesh(name):
        return os.path.join(root, "data", "meshes", name + ".obj")

    def o(name):
        return os.path.join(out_dir, name)
    missing = o("no_such_folder/x")
    table = [
        ("subdivide", ["subdivide", mesh("cube"), "--scheme", "catmull-clark", "-o", o("s.obj")], [o("s.obj")],
         ["--levels", "--max-faces", "--threads"]),
        ("eval", ["eval", mesh("cube"), "--scheme", "catmull-clark", "--grid", "1", "-o", o("e.json")], [o("e.json")],
         ["--grid", "--threads"]),
        ("measure", ["measure", mesh("cube"), "--scheme", "catmull-clark", "--degree", "4", "--tiles", "2"], [],
         ["--degree", "--tiles"]),
        ("volume", ["volume", mesh("cube"), "--scheme", "catmull-clark"], [], ["--levels", "--degree", "--tiles"]),
        ("poisson", ["poisson", mesh("cube"), "--scheme", "catmull-clark", "--level", "1", "--rhs", "x", "-o",
                     o("p.vtk")], [o("p.vtk")], ["--level", "--reference-level", "--boundary-value", "--rhs"]),
        ("poisson iga", ["poisson", mesh("cube"), "--scheme", "catmull-clark", "--method", "iga", "--degree", "2",
                         "--tiles", "1", "--rhs", "x", "-o", o("p.vtk")], [o("p.vtk")], ["--degree", "--tiles"]),
        ("eigen", ["eigen", "--scheme", "catmull-clark", "--valence", "5"], [], ["--valence", "--rings"]),
        ("plate", ["plate", mesh("plate_sym"), "--degree", "2", "-o", o("w.vtk")], [o("w.vtk")],
         ["--pressure", "--levels", "--thickness", "--E", "--nu", "--degree", "--decide-level"]),
        ("shell", ["shell", mesh("shell_scordelis_lo"), "--E", "4.32e8", "--nu", "0", "--thickness", "0.25",
                   "--gravity", "90", "--fix", "abs(y) > 24.999:xz", "--degree", "3", "--tiles", "1"], [],
         ["--E", "--nu", "--thickness", "--gravity", "--pressure", "--levels", "--degree", "--tiles"]),
        ("render", ["render", mesh("cube"), "--scheme", "catmull-clark", "-o", o("r.png"), "--size", "64x64",
                    "--resolution", "2", "--field", "mean-curvature"], [o("r.png")],
         ["--isolines", "--resolution", "--supersampling"]),
        ("parameterize", ["parameterize", mesh("disk_ev7_tris"), "--scheme", "loop", "--method", "dec", "-o",
                          o("uv.ply"), "--texture-png", o("uv.png"), "--size", "64x64"], [o("uv.ply"), o("uv.png")],
         ["--squares", "--degree", "--tiles"]),
        ("geodesic", ["geodesic", mesh("cube"), "--scheme", "catmull-clark", "--source", "0", "--level", "1", "-o",
                      o("g.ply"), "--png", o("g.png")], [o("g.ply"), o("g.png")],
         ["--source", "--level", "--time-factor", "--reference-level", "--isolines", "--gradient-degree"]),
        ("vector-field", ["vector-field", mesh("cube"), "--scheme", "catmull-clark", "--method", "dec", "--source",
                          "0:1", "--sink", "6:1", "--save-one-form", o("w.txt"), "-o", o("v.vtk"), "--png",
                          o("v.png")], [o("w.txt"), o("v.vtk"), o("v.png")],
         ["--weight", "--sample-level", "--level"]),
        ("hodge", ["hodge", mesh("genus2"), "--scheme", "catmull-clark", "--method", "dec", "--random", "1",
                   "--save-parts", o("p_"), "-o", o("h.vtk")],
         [o("p_exact.txt"), o("p_coexact.txt"), o("p_harmonic.txt"), o("h.vtk")],
         ["--random", "--sample-level", "--level"]),
        ("membrane", ["membrane", mesh("octahedron"), "--scheme", "loop", "--area", "12.566370614359172",
                      "--reduced-volume", "0.9", "--max-iterations", "3", "-o", o("m.obj")], [o("m.obj")],
         ["--area", "--reduced-volume", "--mean-curvature", "--reduced-mean-curvature", "--spontaneous-curvature",
          "--regularize-harmonic", "--tolerance", "--degree"]),
        ("membrane volume", ["membrane", mesh("octahedron"), "--scheme", "loop", "--area", "12.566370614359172",
                             "--volume", "3", "--max-iterations", "3", "-o", o("m.obj")], [o("m.obj")], ["--volume"]),
        ("tune", ["tune", "--valence", "5", "--lambda", "0.55"], [], ["--lambda", "--quadrature", "--poisson-ratio"]),
        ("reverse", ["reverse", mesh("quad_torus"), "-o", o("rv.obj")], [o("rv.obj")], ["--levels", "--tolerance"]),
        ("elasticity", ["elasticity", mesh("quad_grid"), "--boundary", "loaded", "--clamp", "left", "--traction",
                        "right:0.1,0", "--plane-stress", "--resolution", "2", "--no-stiffness", "-o", o("el.vtk")],
         [o("el.vtk")], ["--E", "--nu", "--levels", "--resolution"]),
    ]
    def with_value(argv, option, value):  # replaces the option's value, or adds the option
        if option in argv:
            k = argv.index(option)
            return argv[:k + 1] + [value] + argv[k + 2:]
        return argv + [option, value]

    runs = []
    for label, argv, outputs, options in table:
        for option in options:
            for value in HOSTILE_NUMBERS:
                runs.append(("%s %s %s" % (label, option, value), with_value(argv, option, value), outputs))
        # Each output in a missing folder, the others where they were: nothing may be written.
        for k in range(len(argv)):
            if argv[k] in outputs or (label == "hodge" and argv[k] == o("p_")):
                bad = list(argv)
                bad[k] = missing + os.path.splitext(argv[k])[1]
                runs.append(("%s %s in a missing folder" % (label, argv[k - 1]), bad, outputs))
    return runs


def check(limsurf, name, label, argv, outputs, out_dir, is_huge):
    """Runs one command; returns a list of problems (empty when it kept the promise)."""
    limit = HUGE_SECONDS if is_huge else SLOW_SECONDS
    # A run over its bound is timed once more and the faster run counts: a busy machine (another
    # build, a noisy neighbour) can push a 0.3 s run past 1 s once, while a hang or a quadratic
    # blow-up is over the bound every time.
    for attempt in range(2):
        for path in os.listdir(out_dir):
            os.remove(os.path.join(out_dir, path))
        start = time.monotonic()
        try:
            run = subprocess.run([limsurf] + argv, capture_output=True, timeout=min(max(limit * 3, 10), 300),
                                 cwd=out_dir)
        except subprocess.TimeoutExpired:
            return ["%s | %s: did not finish (a hang)" % (name, label)]
        seconds = time.monotonic() - start
        if seconds <= limit:
            break
    problems = []
    where = "%s | %s" % (name, label)
    out = run.stdout.decode("utf-8", "replace")
    err = run.stderr.decode("utf-8", "replace")
    err_lines = [line for line in err.splitlines() if line]
    if seconds > limit:
        problems.append("%s: took %.2f s (limit %.1f s)" % (where, seconds, limit))
    if run.returncode not in (0, 1, 2):
        problems.append("%s: exit code %d: %s" % (where, run.returncode, err[-300:]))
        return problems
    written = sorted(os.listdir(out_dir))
    if run.returncode != 0:
        errors = [line for line in err_lines if line.startswith("error:")]
        if len(errors) != 1 or not err_lines or not err_lines[-1].startswith("error:"):
            problems.append("%s: expected one final 'error:' line, got: %r" % (where, err[-400:]))
        if written:
            problems.append("%s: failed but left files %s" % (where, written))
    else:
        if NON_FINITE.search(out):
            problems.append("%s: nan/inf on stdout: %s" % (where, NON_FINITE.search(out).group(0)))
        for path in outputs:
            binary = os.path.splitext(path)[1] in (".png", ".glb")  # compressed bytes may spell "inf"
            if os.path.exists(path) and not binary and \
                    NON_FINITE.search(open(path, "rb").read().decode("utf-8", "replace")):
                problems.append("%s: nan/inf in %s" % (where, os.path.basename(path)))
            if os.path.exists(path) and os.path.splitext(path)[1] in (".obj", ".off", ".ply"):
                back = subprocess.run([limsurf, "info", path], capture_output=True, timeout=60)
                if back.returncode != 0:
                    problems.append("%s: wrote %s that limsurf does not read back: %s"
                                    % (where, os.path.basename(path), back.stderr.decode()[-200:]))
        strays = [f for f in written if os.path.join(out_dir, f) not in outputs]
        if strays:
            problems.append("%s: left unexpected files %s" % (where, strays))
    warnings = [line for line in err_lines if line.startswith("warning:")]
    if len(warnings) > MAX_WARNING_LINES:
        problems.append("%s: %d warning lines (at most %d)" % (where, len(warnings), MAX_WARNING_LINES))
    return problems


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("limsurf")
    parser.add_argument("root")
    parser.add_argument("work")
    parser.add_argument("--huge", type=int, default=100000, help="face corners of each huge input")
    parser.add_argument("--time-scale", type=float, default=1.0,
                        help="multiply the time bounds (Debug and sanitizer builds run 5-20x slower)")
    parser.add_argument("--inputs", help="a folder of meshes to replay instead of the corpus and generated inputs")
    args = parser.parse_args()
    # Each run's working directory is its output folder: relative paths would not resolve there.
    args.limsurf, args.root, args.work = (os.path.abspath(p) for p in (args.limsurf, args.root, args.work))
    args.inputs = os.path.abspath(args.inputs) if args.inputs else None
    global HUGE_SECONDS, SLOW_SECONDS
    HUGE_SECONDS *= args.time_scale
    SLOW_SECONDS *= args.time_scale
    if os.path.exists(args.work):
        shutil.rmtree(args.work)
    os.makedirs(args.work)
    if args.inputs:
        inputs = {name: (os.path.join(args.inputs, name), False) for name in sorted(os.listdir(args.inputs))
                  if os.path.splitext(name)[1] in (".obj", ".off", ".ply")}
    else:
        inputs = dict(corpus(args.root))
        inputs.update(generate(args.work, args.huge))
    jobs = []
    for index, (name, (path, is_huge)) in enumerate(sorted(inputs.items())):
        for label, argv, outputs in commands(path, "@OUT@", is_huge):
            jobs.append((name, label, argv, outputs, is_huge, index))
    if args.inputs:
        return run_jobs(args, jobs)
    for label, argv, outputs in standalone("@OUT@"):
        jobs.append(("no input", label, argv, outputs, False, len(inputs)))
    for label, argv, outputs in elasticity_cases(args.root, args.work, "@OUT@"):
        jobs.append(("bundled cells", label, argv, outputs, False, len(inputs)))
    for label, argv, outputs in option_cases(args.root, "@OUT@"):
        jobs.append(("options", label, argv, outputs, False, len(inputs)))
    return run_jobs(args, jobs)


def run_jobs(args, jobs):
    """Runs @p jobs (two at a time, the huge ones alone); prints the failures and the count."""
    local = threading.local()  # one output folder per worker thread

    def run_job(job):
        name, label, argv, outputs, is_huge, _ = job
        if not hasattr(local, "out_dir"):
            local.out_dir = os.path.join(args.work, "out-%d" % threading.get_ident())
            os.makedirs(local.out_dir)
        out_dir = local.out_dir
        fix = lambda s: s.replace("@OUT@", out_dir)
        return check(args.limsurf, name, label, [fix(a) for a in argv], [fix(o) for o in outputs], out_dir, is_huge)

    # Huge inputs run alone (their time bound is tight); the others two at a time.
    problems = []
    passed = 0
    small = [j for j in jobs if not j[4]]
    huge = [j for j in jobs if j[4]]
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        for result in pool.map(run_job, small):
            problems += result
            passed += not result
    for job in huge:
        result = run_job(job)
        problems += result
        passed += not result
    for problem in problems:
        print("FAIL " + problem)
    print("%d passed, %d failed" % (passed, len(jobs) - passed))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
