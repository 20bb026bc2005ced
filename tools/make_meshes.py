#!/usr/bin/env python3
"""Generate limsurf's bundled example meshes and their test oracle.

Writes every mesh into data/meshes/<name>.obj, a generated table
data/meshes/README.md, and tests/data/bundled_meshes.csv (the expected
topological invariants the C++ tests compare against).

Standard library only, deterministic: running it twice gives byte-identical
output. `--check` regenerates into a temporary directory and exits non-zero
when the committed files differ.

Independence of the oracle: V/E/F are counted here from the script's own
undirected-edge set; genus, boundary loops and components are the values known
from each construction. The script then asserts that V - E + F equals
2*components - 2*genus - boundary_loops, that its own boundary walk and
union-find agree with the construction, and that every mesh is a consistently
oriented 2-manifold with outward (counter-clockwise) faces. Any failure aborts.

Coordinates are rounded to 12 decimals (and -0.0 normalised to 0.0) before
use, so the OBJ files do not depend on the last bit of the platform's libm;
each float is then written with repr(), which round-trips exactly.
"""

import argparse
import filecmp
import math
import os
import sys
import tempfile

SCRIPT = "tools/make_meshes.py"
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MESH_SUBDIR = os.path.join("data", "meshes")
CSV_PATH = os.path.join("tests", "data", "bundled_meshes.csv")

CSV_HEADER = (
    "name,file,num_vertices,num_edges,num_faces,euler_characteristic,genus,"
    "num_boundary_loops,num_components,closed,triangles_only,quads_only,"
    "extraordinary_valences,description"
)


class MeshError(Exception):
    pass


# --------------------------------------------------------------------------
# Small vector helpers
# --------------------------------------------------------------------------

def clean(x):
    """Round to 12 decimals and normalise -0.0, so output is platform-stable."""
    return round(x, 12) + 0.0


def vsub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def vadd(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def vscale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(dot(a, a))


def normalize(a):
    n = norm(a)
    return (a[0] / n, a[1] / n, a[2] / n)


# --------------------------------------------------------------------------
# Mesh container
# --------------------------------------------------------------------------

class Mesh:
    """A polygon mesh with its construction-known invariants."""

    def __init__(self, name, description, verts, faces, genus, boundary_loops, components,
                 orientation, required_valences=()):
        self.name = name
        self.description = description
        self.verts = [tuple(clean(c) for c in v) for v in verts]
        self.faces = [tuple(f) for f in faces]
        self.genus = genus
        self.boundary_loops = boundary_loops
        self.components = components
        # "volume" (closed: signed volume > 0 per component), "plus_z" (planar,
        # normals +z), "radial_y"/"radial_z" (about the y/z axis, normals outward) or
        # "radial_o" (about the origin, normals outward).
        self.orientation = orientation
        # Valences the construction guarantees to be present (e.g. the poles).
        self.required_valences = tuple(required_valences)
        # OpenSubdiv subdivision tags ("t crease 2/1/0 0 1 10.0"), 0-based, written after the faces.
        self.tags = []
        # Material group name per face (written as `usemtl NAME` before each run), or None.
        self.face_groups = None
        # Periodic unit-square meshes: boundary only on the sides of [0 1]^2, opposite sides with the
        # same node coordinates, each square corner a corner of one face, every face convex.
        self.periodic_square = False


class Builder:
    """Collects vertices keyed by a construction label, so shared vertices are welded."""

    def __init__(self):
        self.verts = []
        self.index = {}
        self.faces = []

    def vertex(self, key, pos):
        if key not in self.index:
            self.index[key] = len(self.verts)
            self.verts.append(pos)
        return self.index[key]

    def face(self, ids):
        self.faces.append(tuple(ids))


# --------------------------------------------------------------------------
# Convex polyhedra from vertices + known outward face normals
# --------------------------------------------------------------------------

def hull_faces(verts, normals):
    """For each outward normal, the vertices maximising dot(v, n), sorted CCW about n."""
    faces = []
    for n in normals:
        dots = [dot(v, n) for v in verts]
        top = max(dots)
        ids = [i for i, d in enumerate(dots) if d > top - 1e-9]
        if len(ids) < 3:
            raise MeshError("hull face with fewer than 3 vertices")
        c = (0.0, 0.0, 0.0)
        for i in ids:
            c = vadd(c, verts[i])
        c = vscale(c, 1.0 / len(ids))
        u = normalize(vsub(verts[ids[0]], c))
        w = cross(n, u)
        ids.sort(key=lambda i: math.atan2(dot(vsub(verts[i], c), w), dot(vsub(verts[i], c), u)) % (2 * math.pi))
        k = ids.index(min(ids))
        faces.append(tuple(ids[k:] + ids[:k]))
    return faces


PHI = (1.0 + math.sqrt(5.0)) / 2.0


def icosahedron_verts():
    """Regular icosahedron, unit circumradius."""
    raw = []
    for a in (-1.0, 1.0):
        for b in (-PHI, PHI):
            raw.append((0.0, a, b))
            raw.append((a, b, 0.0))
            raw.append((b, 0.0, a))
    return [normalize(v) for v in raw]


def dodecahedron_verts():
    """Regular dodecahedron, unit circumradius."""
    raw = []
    for x in (-1.0, 1.0):
        for y in (-1.0, 1.0):
            for z in (-1.0, 1.0):
                raw.append((x, y, z))
    ip = 1.0 / PHI
    for a in (-ip, ip):
        for b in (-PHI, PHI):
            # (0, +-phi, +-1/phi) and cyclic: the dual orientation of icosahedron_verts().
            raw.append((0.0, b, a))
            raw.append((b, a, 0.0))
            raw.append((a, 0.0, b))
    return [normalize(v) for v in raw]


def cube_verts(half=0.5, centre=(0.0, 0.0, 0.0)):
    vs = []
    for x in (-half, half):
        for y in (-half, half):
            for z in (-half, half):
                vs.append(vadd(centre, (x, y, z)))
    return vs


AXES = [(1.0, 0.0, 0.0), (-1.0, 0.0, 0.0), (0.0, 1.0, 0.0),
        (0.0, -1.0, 0.0), (0.0, 0.0, 1.0), (0.0, 0.0, -1.0)]


def tetra_verts(centre=(0.0, 0.0, 0.0), scale=1.0):
    """Regular tetrahedron inscribed in a cube; unit circumradius times scale."""
    s = scale / math.sqrt(3.0)
    raw = [(1.0, 1.0, 1.0), (1.0, -1.0, -1.0), (-1.0, 1.0, -1.0), (-1.0, -1.0, 1.0)]
    return [vadd(centre, vscale(v, s)) for v in raw]


TETRA_NORMALS = [(-1.0, -1.0, -1.0), (-1.0, 1.0, 1.0), (1.0, -1.0, 1.0), (1.0, 1.0, -1.0)]


# --------------------------------------------------------------------------
# Mesh constructions
# --------------------------------------------------------------------------

def make_cube():
    vs = cube_verts()
    return Mesh("cube", "axis-aligned unit cube (edge 1) centred at the origin; 6 quads",
                vs, hull_faces(vs, AXES), 0, 0, 1, "volume", (3,))


def make_cube_creases():
    """The cube with OpenSubdiv tags: the 4 edges of the top face infinitely
    sharp, one vertical edge semi-sharp (2.5), one bottom vertex a corner."""
    vs = cube_verts()
    mesh = Mesh("cube_creases", "unit cube with OpenSubdiv tags: 4 infinitely sharp top edges; "
                "1 semi-sharp (2.5) vertical edge; 1 corner vertex", vs, hull_faces(vs, AXES), 0, 0, 1, "volume", (3,))
    top = [i for i, v in enumerate(mesh.verts) if v[2] > 0]
    bottom = [i for i, v in enumerate(mesh.verts) if v[2] < 0]
    top_face = next(f for f in mesh.faces if all(i in top for i in f))
    for k in range(4):
        mesh.tags.append("t crease 2/1/0 %d %d 10.0" % (top_face[k], top_face[(k + 1) % 4]))
    below = next(i for i in bottom if mesh.verts[i][:2] == mesh.verts[top_face[0]][:2])
    mesh.tags.append("t crease 2/1/0 %d %d 2.5" % (top_face[0], below))
    mesh.tags.append("t corner 1/1/0 %d 10.0" % bottom[-1])
    return mesh


def make_tetrahedron():
    vs = tetra_verts()
    return Mesh("tetrahedron", "regular tetrahedron with unit circumradius",
                vs, hull_faces(vs, TETRA_NORMALS), 0, 0, 1, "volume", (3,))


def make_octahedron():
    vs = [(1.0, 0.0, 0.0), (-1.0, 0.0, 0.0), (0.0, 1.0, 0.0),
          (0.0, -1.0, 0.0), (0.0, 0.0, 1.0), (0.0, 0.0, -1.0)]
    normals = [(x, y, z) for x in (-1.0, 1.0) for y in (-1.0, 1.0) for z in (-1.0, 1.0)]
    return Mesh("octahedron", "regular octahedron with unit circumradius (vertices at +-e_i)",
                vs, hull_faces(vs, normals), 0, 0, 1, "volume", (4,))


def make_icosahedron():
    vs = icosahedron_verts()
    return Mesh("icosahedron", "regular icosahedron with unit circumradius",
                vs, hull_faces(vs, dodecahedron_verts()), 0, 0, 1, "volume", (5,))


def make_dodecahedron():
    vs = dodecahedron_verts()
    return Mesh("dodecahedron", "regular dodecahedron with unit circumradius; 12 pentagons",
                vs, hull_faces(vs, icosahedron_verts()), 0, 0, 1, "volume", (3,))


def torus_grid(nu, nv, major=1.0, minor=0.4):
    """Grid vertices (i around the z axis, j around the tube) and CCW quads (outward)."""
    vs = []
    for i in range(nu):
        u = 2.0 * math.pi * i / nu
        for j in range(nv):
            v = 2.0 * math.pi * j / nv
            r = major + minor * math.cos(v)
            vs.append((r * math.cos(u), r * math.sin(u), minor * math.sin(v)))

    def vid(i, j):
        return (i % nu) * nv + (j % nv)

    quads = []
    for i in range(nu):
        for j in range(nv):
            quads.append((vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)))
    return vs, quads


def split_quads(quads):
    """Split every quad (a, b, c, d) along the diagonal a-c."""
    tris = []
    for a, b, c, d in quads:
        tris.append((a, b, c))
        tris.append((a, c, d))
    return tris


def make_quad_torus():
    vs, quads = torus_grid(8, 6)
    return Mesh("quad_torus", "torus (R=1 r=0.4) as an 8x6 grid of quads; all valences 4",
                vs, quads, 1, 0, 1, "volume", (4,))


def make_tri_torus():
    vs, quads = torus_grid(8, 6)
    return Mesh("tri_torus", "the quad_torus grid with every quad split along one diagonal; all valences 6",
                vs, split_quads(quads), 1, 0, 1, "volume", (6,))


def make_genus2():
    """Outer surface of a 5x3x1 slab of voxels with two one-voxel holes (a figure 8)."""
    holes = {(1, 1), (3, 1)}
    cells = {(x, y, 0) for x in range(5) for y in range(3) if (x, y) not in holes}
    scale = 0.5
    offset = (-2.5, -1.5, -0.5)
    b = Builder()

    def corner(p):
        return b.vertex(p, tuple(scale * (p[k] + offset[k]) for k in range(3)))

    for cell in sorted(cells):
        for axis in range(3):
            for sign in (1, -1):
                nb = list(cell)
                nb[axis] += sign
                if tuple(nb) in cells:
                    continue
                # Face of the voxel on the side (axis, sign); tangent axes u, w
                # with u x w = +e_axis.
                ua, wa = (axis + 1) % 3, (axis + 2) % 3
                base = list(cell)
                if sign > 0:
                    base[axis] += 1
                pts = []
                for du, dw in ((0, 0), (1, 0), (1, 1), (0, 1)):
                    p = list(base)
                    p[ua] += du
                    p[wa] += dw
                    pts.append(tuple(p))
                if sign < 0:
                    pts.reverse()
                b.face([corner(p) for p in pts])
    return Mesh("genus2", "closed genus-2 quad surface: boundary of a 5x3x1 voxel slab with two holes (scaled 0.5)",
                b.verts, b.faces, 2, 0, 1, "volume", (3, 5))


def make_sphere_quads():
    """Cube faces split 2x bilinearly (4x4 quads each), projected to the unit sphere."""
    n = 4
    b = Builder()
    for axis in range(3):
        for sign in (1, -1):
            ua, wa = (axis + 1) % 3, (axis + 2) % 3
            if sign < 0:
                ua, wa = wa, ua

            def point(i, j, axis=axis, sign=sign, ua=ua, wa=wa):
                p = [0, 0, 0]
                p[axis] = sign * n
                p[ua] = 2 * i - n
                p[wa] = 2 * j - n
                key = tuple(p)
                return b.vertex(key, normalize(tuple(float(c) for c in key)))

            for i in range(n):
                for j in range(n):
                    b.face([point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)])
    return Mesh("sphere_quads", "unit cube split twice bilinearly (4x4 quads per face) projected to the unit sphere",
                b.verts, b.faces, 0, 0, 1, "volume", (3,))


def make_sphere_tris():
    base = icosahedron_verts()
    base_faces = hull_faces(base, dodecahedron_verts())
    b = Builder()
    for i, v in enumerate(base):
        b.vertex(("v", i), v)
    for f in base_faces:
        a, c, d = f
        mids = []
        for p, q in ((a, c), (c, d), (d, a)):
            key = ("e", min(p, q), max(p, q))
            mids.append(b.vertex(key, normalize(vscale(vadd(base[p], base[q]), 0.5))))
        mab, mbc, mca = mids
        b.face((a, mab, mca))
        b.face((c, mbc, mab))
        b.face((d, mca, mbc))
        b.face((mab, mbc, mca))
    return Mesh("sphere_tris", "icosphere level 1: icosahedron split 1-to-4 and projected to the unit sphere",
                b.verts, b.faces, 0, 0, 1, "volume", (5,))


def make_tetra_sphere(j):
    """F_tetra,j of the C2g0 paper (Fig. 6): the tetrahedron split 1-to-4 j times, every new
    midpoint projected to the unit sphere; valences 3 (the four original vertices) and 6."""
    verts = [normalize(v) for v in tetra_verts()]
    faces = hull_faces(verts, TETRA_NORMALS)
    for _ in range(j):
        b = Builder()
        for i, v in enumerate(verts):
            b.vertex(("v", i), v)
        for a, c, d in faces:
            mids = []
            for p, q in ((a, c), (c, d), (d, a)):
                key = ("e", min(p, q), max(p, q))
                mids.append(b.vertex(key, normalize(vscale(vadd(verts[p], verts[q]), 0.5))))
            mab, mbc, mca = mids
            b.face((a, mab, mca))
            b.face((c, mbc, mab))
            b.face((d, mca, mbc))
            b.face((mab, mbc, mca))
        verts, faces = b.verts, b.faces
    return Mesh("tetra_%d" % j,
                "F_tetra_%d (C2g0 paper Fig. 6): the tetrahedron split 1-to-4 %d times with midpoints projected "
                "to the unit sphere; valences 3 and 6" % (j, j),
                verts, faces, 0, 0, 1, "volume", (3,))


def make_c2g0_torus(nu, nv):
    vs, quads = torus_grid(nu, nv)
    return Mesh("torus_%dx%d" % (nu, nv),
                "torus (R=1 r=0.4) as a %dx%d grid with quads split along one diagonal; all valences 6 "
                "(C2g0 paper Fig. 6)" % (nu, nv),
                vs, split_quads(quads), 1, 0, 1, "volume", (6,))


def ev35_pattern(lines):
    """The square as a 4x4 grid on the lines `lines` (five x = y values) whose central 2x2 block is
    re-quadded around its centre to the block's corners: the block's corners get valence 5, its edge
    midpoints valence 3; fourfold symmetric when the lines are."""
    n = 4
    vs = [(lines[i], lines[j], 0.0) for j in range(n + 1) for i in range(n + 1)]

    def vid(i, j):
        return j * (n + 1) + i

    quads = [(vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)) for j in range(n) for i in range(n)]
    quads = [q for q in quads if not all(1 <= (v % (n + 1)) <= 3 and 1 <= (v // (n + 1)) <= 3 for v in q)]
    ring = [vid(1, 1), vid(2, 1), vid(3, 1), vid(3, 2), vid(3, 3), vid(2, 3), vid(1, 3), vid(1, 2)]
    c = vid(2, 2)
    quads += [(c, ring[k], ring[k + 1], ring[(k + 2) % 8]) for k in range(0, 8, 2)]
    # The valence-3 vertices (the block's edge midpoints) would make straight angles in the new
    # quads: move them a fifth of their distance from the centre outwards (still symmetric).
    for k in range(1, 8, 2):
        x, y, z = vs[ring[k]]
        vs[ring[k]] = (x + 0.2 * (x - 5.0), y + 0.2 * (y - 5.0), z)
    return vs, quads


def split_quads_bilinear(vs, quads):
    """Each quad into four through its edge midpoints and centroid (no smoothing: the same surface)."""
    vs = list(vs)
    mids = {}

    def mid(a, b):
        key = (min(a, b), max(a, b))
        if key not in mids:
            mids[key] = len(vs)
            vs.append(vscale(vadd(vs[a], vs[b]), 0.5))
        return mids[key]

    out = []
    for q in quads:
        f = len(vs)
        vs.append(tuple(sum(vs[v][c] for v in q) / 4.0 for c in range(3)))
        m = [mid(q[i], q[(i + 1) % 4]) for i in range(4)]
        out += [(q[i], m[i], f, m[i - 1]) for i in range(4)]
    return vs, out


def make_plate_ev35():
    """The plate [0 10]^2 as ev35_pattern on the uniform 4x4 grid: four interior vertices of valence
    3 and four of valence 5, symmetric."""
    vs, quads = ev35_pattern([0.0, 2.5, 5.0, 7.5, 10.0])
    return Mesh("plate_ev35", "the plate [0 10]^2 (the seed's L = 10): a 4x4 quad grid whose central 2x2 "
                "block is re-quadded to give four interior vertices of valence 3 (moved outwards by 0.5) and four "
                "of valence 5",
                vs, quads, 0, 1, 1, "plus_z", (3, 5))


def make_plate_sym():
    """The seed's §4.1-4.2 example (Fig. 8a): ev35_pattern on the lines 0, 1.5, 5, 8.5, 10, split
    once without smoothing, so that each valence-5 vertex's limit point lies at (1.786, 1.786) and its
    images: where Navier's solution under the sinusoidal load has the seed's R = 29.2 (on the
    diagonal, R = 29.3 at x = 1.76), and under the uniform load is saddle-shaped."""
    vs, quads = split_quads_bilinear(*ev35_pattern([0.0, 1.5, 5.0, 8.5, 10.0]))
    return Mesh("plate_sym", "the plate [0 10]^2 with fourfold symmetry (the seed's Fig. 8a stand-in): the "
                "plate_ev35 pattern on the lines 0 1.5 5 8.5 10; each quad split in four without smoothing; four "
                "interior vertices of valence 5 (limit points x = y = 1.786 and images) and four of valence 3",
                vs, quads, 0, 1, 1, "plus_z", (3, 5))


def make_plate_flip():
    """The seed's §4.3 example (Fig. 8b): a 5x4 grid on uneven lines with the edge between two
    neighbouring cells rotated, which gives two vertices of valence 5 (limit points (2.17, 2.21),
    in a cup of the sinusoidal load's solution, and (5.08, 4.67), at its central saddle) and two of
    valence 3, moved half a unit apart so that no angle is straight. No symmetry."""
    xs, ys = [0.0, 1.8, 3.6, 5.4, 7.6, 10.0], [0.0, 1.8, 5.0, 7.4, 10.0]
    nx = len(xs)

    def vid(i, j):
        return j * nx + i

    vs = [(x, y, 0.0) for y in ys for x in xs]
    quads = [(vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1))
             for j in range(len(ys) - 1) for i in range(nx - 1) if not (j == 1 and i in (1, 2))]
    # Cells (1, 1) and (2, 1) form a hexagon h; its middle edge h1-h4 becomes h0-h3.
    h = [vid(1, 1), vid(2, 1), vid(3, 1), vid(3, 2), vid(2, 2), vid(1, 2)]
    quads += [(h[0], h[1], h[2], h[3]), (h[0], h[3], h[4], h[5])]
    vs[h[1]] = vadd(vs[h[1]], (0.0, -0.5, 0.0))
    vs[h[4]] = vadd(vs[h[4]], (0.0, 0.5, 0.0))
    return Mesh("plate_flip", "the plate [0 10]^2 without symmetry (the seed's Fig. 8b stand-in): a 5x4 quad grid "
                "on the lines x = 0 1.8 3.6 5.4 7.6 10 and y = 0 1.8 5 7.4 10 with one edge rotated; two interior "
                "vertices of valence 5 (limit points (2.17 2.21) and (5.08 4.67)) and two of valence 3",
                vs, quads, 0, 1, 1, "plus_z", (3, 5))


def make_plate_asym():
    """The plate [0 10]^2 as an asymmetric partition into six polygons (a hexagon, three pentagons,
    a quad and a triangle) split Catmull-Clark style into quads (face point, edge midpoints), so the
    face points have valences 6, 5, 5, 5, 4, 3 and four interior corners of the partition valence 3.
    Every square corner lies in one face; the corners were placed for the fine quads' angles (35-146
    degrees)."""
    p = {"P0": (0.0, 0.0), "P1": (3.2, 0.0), "P2": (10.0, 0.0), "P3": (10.0, 3.2), "P4": (10.0, 10.0),
         "P5": (6.6, 10.0), "P6": (0.0, 10.0), "P7": (0.0, 6.2),
         "A": (3.8, 2.8), "K": (5.4, 4.2), "B": (7.8, 4.5), "C": (6.1, 8.5), "E": (2.3, 6.0)}
    polygons = [("P7", "P0", "P1", "A", "E"), ("P1", "P2", "P3", "B", "K", "A"), ("P3", "P4", "P5", "C", "B"),
                ("P5", "P6", "P7", "E", "C"), ("A", "K", "E"), ("K", "B", "C", "E")]
    b = Builder()
    for name, (x, y) in p.items():  # the partition's corners first: vertices 1-13 of the OBJ
        b.vertex(("V", name), (x, y, 0.0))

    def corner(name):
        x, y = p[name]
        return b.vertex(("V", name), (x, y, 0.0))

    def midpoint(u, v):
        (x0, y0), (x1, y1) = p[u], p[v]
        return b.vertex(("E",) + tuple(sorted((u, v))), ((x0 + x1) / 2, (y0 + y1) / 2, 0.0))

    for k, poly in enumerate(polygons):
        n = len(poly)
        centre = b.vertex(("F", k), (sum(p[v][0] for v in poly) / n, sum(p[v][1] for v in poly) / n, 0.0))
        for i in range(n):
            b.face((corner(poly[i]), midpoint(poly[i], poly[(i + 1) % n]), centre, midpoint(poly[i - 1], poly[i])))
    return Mesh("plate_asym", "the plate [0 10]^2 (the seed's L = 10) without symmetry: six polygons (a hexagon; "
                "three pentagons; a quad; a triangle) split into quads; interior valences 3 (five) and 5 (three) "
                "and 6 (one); boundary regular; each square corner in one face",
                b.verts, b.faces, 0, 1, 1, "plus_z", (3, 5, 6))


# --------------------------------------------------------------------------
# Periodic unit squares for plane elasticity (docs/io.md "Face groups")
# --------------------------------------------------------------------------

def split_polygons(points, polygons):
    """Catmull-Clark topology of a planar partition: each polygon becomes one quad per corner
    (corner, edge midpoint, centroid, edge midpoint). Returns (Builder, parent polygon per quad)."""
    b = Builder()
    for name, (x, y) in points.items():
        b.vertex(("V", name), (x, y, 0.0))

    def midpoint(u, v):
        (x0, y0), (x1, y1) = points[u], points[v]
        return b.vertex(("E",) + tuple(sorted((u, v))), ((x0 + x1) / 2, (y0 + y1) / 2, 0.0))

    parent = []
    for k, poly in enumerate(polygons):
        n = len(poly)
        centre = b.vertex(("F", k), (sum(points[v][0] for v in poly) / n, sum(points[v][1] for v in poly) / n, 0.0))
        for i in range(n):
            b.face((b.index[("V", poly[i])], midpoint(poly[i], poly[(i + 1) % n]), centre,
                    midpoint(poly[i - 1], poly[i])))
            parent.append(k)
    return b, parent


def split_quads_in_four(verts, quads):
    """Each quad into four (edge midpoints and the centroid): all new vertices regular."""
    b = Builder()
    for i, p in enumerate(verts):
        b.vertex(("V", i), p)

    def mid(u, v):
        p, q = verts[u], verts[v]
        return b.vertex(("E", min(u, v), max(u, v)), ((p[0] + q[0]) / 2, (p[1] + q[1]) / 2, 0.0))

    for k, q in enumerate(quads):
        c = b.vertex(("F", k), tuple(sum(verts[v][j] for v in q) / 4 for j in range(3)))
        for i in range(4):
            b.face((b.index[("V", q[i])], mid(q[i], q[(i + 1) % 4]), c, mid(q[i - 1], q[i])))
    return b.verts, b.faces


def make_rve_block():
    """The seed's block of material with imperfections (Fig. 20, section 6) as a periodic RVE of the
    unit square: a partition into six polygons (a hexagon, three pentagons, a quad, a triangle) whose
    side points match across opposite sides, split into quads about the centroids (face points of
    valence 6, 5, 5, 5, 4, 3; partition corners of valence 3) and then each quad into four. The faces
    around four vertices are `grain` (the imperfections), the rest `matrix`. The
    partition's inner corners were placed (a search, rounded to 0.01) for the quads' angles (34 to 146
    degrees)."""
    p = {"P0": (0.0, 0.0), "P1": (0.5, 0.0), "P2": (1.0, 0.0), "P3": (1.0, 0.45), "P4": (1.0, 1.0),
         "P5": (0.5, 1.0), "P6": (0.0, 1.0), "P7": (0.0, 0.45),
         "A": (0.46, 0.31), "K": (0.53, 0.45), "B": (0.73, 0.54), "C": (0.51, 0.83), "E": (0.28, 0.5)}
    polygons = [("P7", "P0", "P1", "A", "E"), ("P1", "P2", "P3", "B", "K", "A"), ("P3", "P4", "P5", "C", "B"),
                ("P5", "P6", "P7", "E", "C"), ("A", "K", "E"), ("K", "B", "C", "E")]
    coarse, _ = split_polygons(p, polygons)
    verts, faces = split_quads_in_four(coarse.verts, coarse.faces)
    # Grains: the faces around four vertices: the face points of the hexagon (valence 6) and of the
    # bottom-left and top-right pentagons (valence 5), and the partition corner E: 6 + 5 + 5 + 4 faces.
    def nearest(x, y):
        return min(range(len(verts)), key=lambda v: (verts[v][0] - x) ** 2 + (verts[v][1] - y) ** 2)

    def centroid(poly):
        return (sum(p[v][0] for v in poly) / len(poly), sum(p[v][1] for v in poly) / len(poly))

    centres = [nearest(*centroid(polygons[k])) for k in (1, 0, 2)] + [nearest(*p["E"])]
    groups = ["matrix"] * len(faces)
    for c in centres:
        for k, f in enumerate(faces):
            if c in f:
                if groups[k] == "grain":
                    raise MeshError("rve_block: grains overlap")
                groups[k] = "grain"
    mesh = Mesh("rve_block", "periodic unit square (plane elasticity RVE; the seed's block with imperfections): "
                "six polygons split into quads and each quad into four; interior valences 3 and 5 and 6; side "
                "nodes match across opposite sides; each square corner in one face; usemtl matrix and grain",
                verts, faces, 0, 1, 1, "plus_z", (3, 5, 6))
    mesh.face_groups = groups
    mesh.periodic_square = True
    return mesh


def make_square_inclusion():
    """The unit square with a centred circular inclusion (limit radius 0.25): a frame of grid cells
    (lines 0, 0.08, 0.16 and 0.84, 0.92, 1) around an O-grid: 6 cells per side of the central block
    [0.16 0.84]^2 go in 2 radial cells to 24 interface vertices at 15 degree steps, then in 2 more
    cells to the sides of a 6x6 grid [0.39 0.61]^2 at the centre. The central block's corners get
    valence 5, the inner grid's corners valence 3. The interface edges are infinitely sharp creases,
    so the interface is the closed uniform cubic B-spline of its 24 vertices, placed on the radius R
    with (2 + cos(15 deg)) / 3 * R = 0.25 (the B-spline's radius at its vertices)."""
    m = 6                                   # cells per side of the central block and of the inner grid
    outer = [0.0, 0.08, 0.16]               # frame lines; mirrored about 0.5
    lo, hi = outer[-1], 1.0 - outer[-1]
    lines = outer + [lo + (hi - lo) * i / m for i in range(1, m)] + [1.0 - x for x in reversed(outer)]
    n = len(lines) - 1                      # cells per side of the frame grid
    first = len(outer) - 1                  # grid index of the central block's first line
    radius = 0.75 / (2.0 + math.cos(2.0 * math.pi / (4 * m)))
    half = 0.11                             # half-width of the inner grid
    b = Builder()
    groups = []

    def grid(i, j):
        return b.vertex(("G", i, j), (lines[i], lines[j], 0.0))

    for j in range(n):
        for i in range(n):
            if first <= i < first + m and first <= j < first + m:
                continue
            b.face((grid(i, j), grid(i + 1, j), grid(i + 1, j + 1), grid(i, j + 1)))
            groups.append("matrix")

    # The central block's boundary walked counter-clockwise: 4m points, point 0 at its
    # lower-left corner; the interface and the inner grid's boundary are walked the same way.
    def block_index(k):
        side, t = divmod(k % (4 * m), m)
        return [(first + t, first), (first + m, first + t), (first + m - t, first + m), (first, first + m - t)][side]

    def inner_point(k):
        side, t = divmod(k % (4 * m), m)
        s = -half + 2.0 * half * t / m
        return [(s, -half), (half, s), (-s, half), (-half, -s)][side]

    def ring(level, k):
        """Vertex k of ring `level`: 0 the central block, 2 the interface, 4 the inner grid's boundary."""
        k %= 4 * m
        if level == 0:
            return grid(*block_index(k))
        if level == 4:
            x, y = inner_point(k)
            return b.vertex(("I", round(x, 12), round(y, 12)), (0.5 + x, 0.5 + y, 0.0))
        angle = 2.0 * math.pi * (k / (4.0 * m)) - 0.75 * math.pi
        circle = (radius * math.cos(angle), radius * math.sin(angle))
        if level == 2:
            return b.vertex(("R", 2, k), (0.5 + circle[0], 0.5 + circle[1], 0.0))
        if level < 2:
            i, j = block_index(k)
            start, t = (lines[i] - 0.5, lines[j] - 0.5), level / 2.0
        else:
            start, t = inner_point(k), (4 - level) / 2.0
        return b.vertex(("R", level, k), (0.5 + circle[0] * t + start[0] * (1 - t),
                                          0.5 + circle[1] * t + start[1] * (1 - t), 0.0))

    for level in range(4):
        for k in range(4 * m):
            b.face((ring(level, k), ring(level, k + 1), ring(level + 1, k + 1), ring(level + 1, k)))
            groups.append("matrix" if level < 2 else "inclusion")

    def inner(i, j):
        x, y = -half + 2.0 * half * i / m, -half + 2.0 * half * j / m
        return b.vertex(("I", round(x, 12), round(y, 12)), (0.5 + x, 0.5 + y, 0.0))

    for j in range(m):
        for i in range(m):
            b.face((inner(i, j), inner(i + 1, j), inner(i + 1, j + 1), inner(i, j + 1)))
            groups.append("inclusion")
    mesh = Mesh("square_inclusion", "periodic unit square with a centred circular inclusion (limit radius 0.25; "
                "volume fraction 0.196): an O-grid in a frame of grid cells; interior valences 3 and 5; the 24 "
                "interface edges infinitely sharp creases; usemtl matrix and inclusion",
                b.verts, b.faces, 0, 1, 1, "plus_z", (3, 5))
    for k in range(4 * m):
        mesh.tags.append("t crease 2/1/0 %d %d 10.0" % (ring(2, k), ring(2, k + 1)))
    mesh.face_groups = groups
    mesh.periodic_square = True
    return mesh


def make_cube_ngons():
    t = 0.25
    vs = [v for v in cube_verts() if v != (0.5, 0.5, 0.5)]
    vs += [(0.5 - t, 0.5, 0.5), (0.5, 0.5 - t, 0.5), (0.5, 0.5, 0.5 - t)]
    normals = AXES + [normalize((1.0, 1.0, 1.0))]
    return Mesh("cube_ngons", "unit cube with one corner truncated: 3 quads + 3 pentagons + 1 triangle",
                vs, hull_faces(vs, normals), 0, 0, 1, "volume", (3,))


def make_prism_hex():
    vs = []
    for z in (-0.5, 0.5):
        for i in range(6):
            a = 2.0 * math.pi * i / 6
            vs.append((math.cos(a), math.sin(a), z))
    normals = [(0.0, 0.0, 1.0), (0.0, 0.0, -1.0)]
    for i in range(6):
        a = 2.0 * math.pi * (i + 0.5) / 6
        normals.append((math.cos(a), math.sin(a), 0.0))
    return Mesh("prism_hex", "regular hexagonal prism (circumradius 1 height 1): 2 hexagons + 6 quads",
                vs, hull_faces(vs, normals), 0, 0, 1, "volume", (3,))


def make_tetra_and_cube():
    tv = tetra_verts(centre=(-1.5, 0.0, 0.0))
    tf = hull_faces(tv, TETRA_NORMALS)
    cv = cube_verts(centre=(1.5, 0.0, 0.0))
    cf = hull_faces(cv, AXES)
    off = len(tv)
    faces = tf + [tuple(i + off for i in f) for f in cf]
    return Mesh("tetra_and_cube", "two components: the tetrahedron at x=-1.5 and the cube at x=+1.5",
                tv + cv, faces, 0, 0, 2, "volume", (3,))


def plane_grid(n, lo=-1.0, hi=1.0):
    vs = []
    for j in range(n + 1):
        for i in range(n + 1):
            vs.append((lo + (hi - lo) * i / n, lo + (hi - lo) * j / n, 0.0))

    def vid(i, j):
        return j * (n + 1) + i

    quads = [(vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1))
             for j in range(n) for i in range(n)]
    return vs, quads


def make_quad_grid():
    vs, quads = plane_grid(4)
    return Mesh("quad_grid", "4x4 quads on [-1 1]^2 in the plane z=0",
                vs, quads, 0, 1, 1, "plus_z", (4,))


def make_tri_grid():
    vs, quads = plane_grid(4)
    return Mesh("tri_grid", "the quad_grid with every quad split along the same diagonal; interior valence 6",
                vs, split_quads(quads), 0, 1, 1, "plus_z", (6,))


def make_disk_ev5_quads():
    """Five sectors (a Catmull-Clark split pentagon), each an n x n quad grid."""
    k, n = 5, 3
    spokes = []
    corners = []
    for i in range(k):
        a = 2.0 * math.pi * i / k
        r = math.cos(math.pi / k)
        spokes.append((r * math.cos(a), r * math.sin(a), 0.0))
        c = a + math.pi / k
        corners.append((math.cos(c), math.sin(c), 0.0))
    b = Builder()

    def point(sec, a, c):
        if a == 0 and c == 0:
            key = ("C",)
        elif c == 0:
            key = ("S", sec, a)
        elif a == 0:
            key = ("S", (sec + 1) % k, c)
        else:
            key = ("I", sec, a, c)
        s, t = a / n, c / n
        m0, m1, p = spokes[sec], spokes[(sec + 1) % k], corners[sec]
        pos = vadd(vadd(vscale(m0, s * (1 - t)), vscale(m1, (1 - s) * t)), vscale(p, s * t))
        return b.vertex(key, pos)

    for sec in range(k):
        for a in range(n):
            for c in range(n):
                b.face([point(sec, a, c), point(sec, a + 1, c), point(sec, a + 1, c + 1), point(sec, a, c + 1)])
    return Mesh("disk_ev5_quads", "planar quad disk: a regular pentagon split into 5 sectors of 3x3 quads; "
                "the centre is the only extraordinary vertex (valence 5)",
                b.verts, b.faces, 0, 1, 1, "plus_z", (5,))


def make_disk_ev7_tris():
    """Seven triangular sectors around the centre, each split into n^2 triangles."""
    k, n = 7, 3
    rim = [(math.cos(2.0 * math.pi * i / k), math.sin(2.0 * math.pi * i / k), 0.0) for i in range(k)]
    b = Builder()

    def point(sec, a, c):
        if a == 0 and c == 0:
            key = ("C",)
        elif c == 0:
            key = ("S", sec, a)
        elif a == 0:
            key = ("S", (sec + 1) % k, c)
        else:
            key = ("I", sec, a, c)
        pos = vadd(vscale(rim[sec], a / n), vscale(rim[(sec + 1) % k], c / n))
        return b.vertex(key, pos)

    for sec in range(k):
        for a in range(n):
            for c in range(n - a):
                b.face([point(sec, a, c), point(sec, a + 1, c), point(sec, a, c + 1)])
                if a + c + 2 <= n:
                    b.face([point(sec, a + 1, c), point(sec, a + 1, c + 1), point(sec, a, c + 1)])
    return Mesh("disk_ev7_tris", "planar triangle disk: 7 sectors of 9 triangles around a centre of valence 7; "
                "all other interior vertices have valence 6",
                b.verts, b.faces, 0, 1, 1, "plus_z", (7,))


def make_cylinder_open():
    k, rows = 8, 3
    vs = []
    for j in range(rows + 1):
        for i in range(k):
            a = 2.0 * math.pi * i / k
            vs.append((0.5 * math.cos(a), 0.5 * math.sin(a), -0.5 + j / rows))

    def vid(i, j):
        return j * k + (i % k)

    quads = [(vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)) for j in range(rows) for i in range(k)]
    return Mesh("cylinder_open", "open tube (radius 0.5 height 1): 8 quads around x 3 rows; two boundary loops",
                vs, quads, 0, 2, 1, "radial_z", (4,))


def make_annulus():
    k, rows = 8, 2
    vs = []
    for j in range(rows + 1):
        r = 0.5 + 0.5 * j / rows
        for i in range(k):
            a = 2.0 * math.pi * i / k
            vs.append((r * math.cos(a), r * math.sin(a), 0.0))

    def vid(i, j):
        return j * k + (i % k)

    quads = [(vid(i, j), vid(i, j + 1), vid(i + 1, j + 1), vid(i + 1, j)) for j in range(rows) for i in range(k)]
    return Mesh("annulus", "planar quad ring (radii 0.5 to 1): 8 quads around x 2 rings; two boundary loops",
                vs, quads, 0, 2, 1, "plus_z", (4,))


def make_single_quad():
    vs = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0)]
    return Mesh("single_quad", "one unit square in the plane z=0", vs, [(0, 1, 2, 3)], 0, 1, 1, "plus_z")


def make_single_triangle():
    vs = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]
    return Mesh("single_triangle", "one right triangle in the plane z=0", vs, [(0, 1, 2)], 0, 1, 1, "plus_z")


def make_hexagon_fan():
    vs = [(0.0, 0.0, 0.0)]
    for i in range(6):
        a = 2.0 * math.pi * i / 6
        vs.append((math.cos(a), math.sin(a), 0.0))
    faces = [(0, 1 + i, 1 + (i + 1) % 6) for i in range(6)]
    return Mesh("hexagon_fan", "6 triangles around a centre of valence 6 (regular hexagon circumradius 1)",
                vs, faces, 0, 1, 1, "plus_z", (6,))


def make_pentagon():
    vs = []
    for i in range(5):
        a = math.pi / 2 + 2.0 * math.pi * i / 5
        vs.append((math.cos(a), math.sin(a), 0.0))
    return Mesh("pentagon", "a single regular pentagon face (circumradius 1) in the plane z=0",
                vs, [(0, 1, 2, 3, 4)], 0, 1, 1, "plus_z")


def sphere_point(polar, azimuth):
    s = math.sin(polar)
    return (s * math.cos(azimuth), s * math.sin(azimuth), math.cos(polar))


def make_quad_valence(k, rings=3):
    """Closed quad sphere with poles of valence k.

    Latitude rings r = 1..rings of k vertices each on the unit sphere, odd and
    even rings offset by half a sector (pi/k). Every vertex at level L (north
    pole = level 0, south pole = rings + 1) owns the "kite" quads below it,
    spanning levels L, L+1, L+2: the north pole owns k kites, each ring vertex
    up to ring rings-1 owns one. Poles have valence k, rings 1 and `rings` have
    valence 3, the rest valence 4.
    """
    b = Builder()
    north = b.vertex("N", (0.0, 0.0, 1.0))
    south = b.vertex("S", (0.0, 0.0, -1.0))
    ring = []
    for r in range(1, rings + 1):
        polar = math.pi * r / (rings + 1)
        off = 0.0 if r % 2 == 1 else 0.5
        ring.append([b.vertex(("R", r, j), sphere_point(polar, 2.0 * math.pi * (j + off) / k))
                     for j in range(k)])
    # Ring r (1-based) vertex j sits at azimuth j + off(r) sectors. For a vertex on an
    # odd ring, the neighbours below at j - 1/2 and j + 1/2 are even-ring indices
    # j - 1 and j; for a vertex on an even ring (at j + 1/2) they are j and j + 1.

    def below(r, j):
        """(left, right) neighbours on ring r+1, seen from outside, left = smaller azimuth."""
        if r % 2 == 1:
            return ring[r][(j - 1) % k], ring[r][j % k]
        return ring[r][j % k], ring[r][(j + 1) % k]

    # North pole kites: N, ring1[j], ring2 between j and j+1, ring1[j+1].
    for j in range(k):
        b.face((north, ring[0][j], ring[1][j], ring[0][(j + 1) % k]))
    for r in range(1, rings):
        for j in range(k):
            top = ring[r - 1][j]
            left, right = below(r, j)
            bottom = south if r + 1 == rings else ring[r + 1][j]
            # Seen from outside (azimuth grows to the right, +z is up),
            # top -> left -> bottom -> right is counter-clockwise.
            b.face((top, left, bottom, right))
    return Mesh("quad_valence_%d" % k,
                "closed quad sphere: poles of valence %d joined by %d latitude rings of %d vertices (kites)"
                % (k, rings, k),
                b.verts, b.faces, 0, 0, 1, "volume", (k,))


def make_tri_valence(k, rings=3):
    """Closed triangle sphere with poles of valence k: caps of k triangles and antiprism bands."""
    b = Builder()
    north = b.vertex("N", (0.0, 0.0, 1.0))
    south = b.vertex("S", (0.0, 0.0, -1.0))
    ring = []
    for r in range(1, rings + 1):
        polar = math.pi * r / (rings + 1)
        off = 0.0 if r % 2 == 1 else 0.5
        ring.append([b.vertex(("R", r, j), sphere_point(polar, 2.0 * math.pi * (j + off) / k))
                     for j in range(k)])
    for j in range(k):
        b.face((north, ring[0][j], ring[0][(j + 1) % k]))
        b.face((south, ring[-1][(j + 1) % k], ring[-1][j]))
    for r in range(rings - 1):
        up, dn = ring[r], ring[r + 1]
        for j in range(k):
            if r % 2 == 0:
                # Upper ring at j, lower ring at j + 1/2.
                b.face((up[j], dn[(j - 1) % k], dn[j]))
                b.face((up[j], dn[j], up[(j + 1) % k]))
            else:
                # Upper ring at j + 1/2, lower ring at j.
                b.face((up[j], dn[j], dn[(j + 1) % k]))
                b.face((up[j], dn[(j + 1) % k], up[(j + 1) % k]))
    return Mesh("tri_valence_%d" % k,
                "closed triangle sphere: poles of valence %d joined by %d latitude rings of %d vertices"
                % (k, rings, k),
                b.verts, b.faces, 0, 0, 1, "volume", (k,))


# The shell obstacle course (limsurf shell, docs/fem.md "Shells"): points of the exact surfaces, for
# `limsurf shell --interpolate` (the control points are moved so that the limit surface passes
# through them). The load and probe points are vertices: their limit points stay put under refinement.

def make_shell_scordelis_lo():
    """Scordelis-Lo roof: a cylindrical panel of radius 25 about the y axis, length 50, opening
    angle 2 x 40 degrees, z up; 8 x 8 quads, so that the midpoint of each free edge is a vertex."""
    radius, length, half_angle, n_phi, n_y = 25.0, 50.0, math.radians(40.0), 8, 8
    vs = []
    for j in range(n_y + 1):
        for i in range(n_phi + 1):
            phi = -half_angle + 2.0 * half_angle * i / n_phi
            vs.append((radius * math.sin(phi), -0.5 * length + length * j / n_y, radius * math.cos(phi)))

    def vid(i, j):
        return j * (n_phi + 1) + i

    quads = [(vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)) for j in range(n_y) for i in range(n_phi)]
    return Mesh("shell_scordelis_lo", "Scordelis-Lo roof (shell obstacle course): points of the cylinder of radius "
                "25 about the y axis; y in [-25 25]; angle +-40 degrees from +z; 8 x 8 quads",
                vs, quads, 0, 1, 1, "radial_y", (2, 3, 4))


def make_shell_pinched_cylinder():
    """Pinched cylinder: radius 300 about the z axis, length 600 (z in [-300 300]); 16 quads around
    x 8 along, so that (+-300, 0, 0) are vertices."""
    radius, length, n_around, n_along = 300.0, 600.0, 16, 8
    vs = []
    for j in range(n_along + 1):
        for i in range(n_around):
            a = 2.0 * math.pi * i / n_around
            vs.append((radius * math.cos(a), radius * math.sin(a), -0.5 * length + length * j / n_along))

    def vid(i, j):
        return j * n_around + (i % n_around)

    quads = [(vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1))
             for j in range(n_along) for i in range(n_around)]
    return Mesh("shell_pinched_cylinder", "pinched cylinder (shell obstacle course): points of the cylinder of "
                "radius 300 about the z axis; z in [-300 300]; 16 quads around x 8 along; two boundary loops",
                vs, quads, 0, 2, 1, "radial_z", (3, 4))


def make_shell_hemisphere():
    """Pinched hemisphere with an 18 degree hole: radius 10, polar angle 18 to 90 degrees, z up;
    16 quads around x 8 rows, so that the four load points (+-10, 0, 0), (0, +-10, 0) are vertices."""
    radius, n_around, n_rows = 10.0, 16, 8
    top, bottom = math.radians(18.0), math.radians(90.0)
    vs = []
    for j in range(n_rows + 1):  # from the equator up, so that faces are counter-clockwise from outside
        polar = bottom + (top - bottom) * j / n_rows
        for i in range(n_around):
            a = 2.0 * math.pi * i / n_around
            vs.append((radius * math.sin(polar) * math.cos(a), radius * math.sin(polar) * math.sin(a),
                       radius * math.cos(polar)))

    def vid(i, j):
        return j * n_around + (i % n_around)

    quads = [(vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1))
             for j in range(n_rows) for i in range(n_around)]
    return Mesh("shell_hemisphere", "pinched hemisphere with an 18 degree hole (shell obstacle course): points of "
                "the sphere of radius 10; polar angle 18 to 90 degrees; 16 quads around x 8 rows; two boundary loops",
                vs, quads, 0, 2, 1, "radial_o", (3, 4))


def all_meshes():
    meshes = [
        make_cube(), make_cube_creases(), make_tetrahedron(), make_octahedron(), make_icosahedron(), make_dodecahedron(),
        make_quad_torus(), make_tri_torus(), make_genus2(), make_sphere_quads(), make_sphere_tris(),
        make_cube_ngons(), make_prism_hex(), make_tetra_and_cube(),
        make_quad_grid(), make_tri_grid(), make_disk_ev5_quads(), make_disk_ev7_tris(),
        make_cylinder_open(), make_annulus(), make_single_quad(), make_single_triangle(),
        make_hexagon_fan(), make_pentagon(),
    ]
    meshes += [make_quad_valence(k) for k in range(3, 9)]
    meshes += [make_tri_valence(k) for k in range(3, 13)]
    meshes += [make_tetra_sphere(j) for j in range(0, 5)]
    meshes += [make_c2g0_torus(4, 5), make_c2g0_torus(8, 10)]
    meshes += [make_plate_ev35(), make_plate_asym(), make_plate_sym(), make_plate_flip()]
    meshes += [make_rve_block(), make_square_inclusion()]
    meshes += [make_shell_scordelis_lo(), make_shell_pinched_cylinder(), make_shell_hemisphere()]
    return meshes


# --------------------------------------------------------------------------
# Independent analysis and self-checks
# --------------------------------------------------------------------------

class UnionFind:
    def __init__(self, n):
        self.parent = list(range(n))

    def find(self, x):
        while self.parent[x] != x:
            self.parent[x] = self.parent[self.parent[x]]
            x = self.parent[x]
        return x

    def union(self, a, b):
        ra, rb = self.find(a), self.find(b)
        if ra != rb:
            self.parent[max(ra, rb)] = min(ra, rb)


def fail(mesh, msg):
    raise MeshError("%s: %s" % (mesh.name, msg))


def analyse(mesh):
    """Counts and checks; returns a dict of the mesh's invariants."""
    nv = len(mesh.verts)
    if mesh.faces == []:
        fail(mesh, "no faces")
    # Faces: indices in range, degree >= 3, no repeated vertex.
    for f in mesh.faces:
        if len(f) < 3:
            fail(mesh, "face %r has degree < 3" % (f,))
        if len(set(f)) != len(f):
            fail(mesh, "face %r repeats a vertex" % (f,))
        for v in f:
            if not 0 <= v < nv:
                fail(mesh, "face %r index out of range" % (f,))
    # No isolated vertices; no two vertices at the same position.
    used = set(v for f in mesh.faces for v in f)
    if len(used) != nv:
        fail(mesh, "%d isolated vertices" % (nv - len(used)))
    keys = set(tuple(round(c, 9) for c in p) for p in mesh.verts)
    if len(keys) != nv:
        fail(mesh, "coincident vertex positions")
    # Directed edges at most once; undirected edges in 1 or 2 faces.
    directed = {}
    undirected = {}
    for fi, f in enumerate(mesh.faces):
        for k in range(len(f)):
            a, c = f[k], f[(k + 1) % len(f)]
            if (a, c) in directed:
                fail(mesh, "directed edge %d->%d used twice (inconsistent orientation)" % (a, c))
            directed[(a, c)] = fi
            undirected.setdefault((min(a, c), max(a, c)), []).append(fi)
    for e, fs in undirected.items():
        if len(fs) not in (1, 2):
            fail(mesh, "edge %r in %d faces" % (e, len(fs)))
    ne = len(undirected)
    nf = len(mesh.faces)
    # Vertex manifoldness: the faces around each vertex form one fan.
    faces_at = [[] for _ in range(nv)]
    for fi, f in enumerate(mesh.faces):
        for v in f:
            faces_at[v].append(fi)
    for v in range(nv):
        local = {fi: i for i, fi in enumerate(faces_at[v])}
        uf = UnionFind(len(local))
        for fi in faces_at[v]:
            f = mesh.faces[fi]
            k = f.index(v)
            for w in (f[(k + 1) % len(f)], f[k - 1]):
                for fj in undirected[(min(v, w), max(v, w))]:
                    uf.union(local[fi], local[fj])
        if len(set(uf.find(i) for i in range(len(local)))) != 1:
            fail(mesh, "vertex %d is non-manifold (more than one fan)" % v)
    # Boundary: directed edges without a twin; walk them into loops.
    boundary_next = {}
    for (a, c) in directed:
        if (c, a) not in directed:
            if a in boundary_next:
                fail(mesh, "vertex %d has two outgoing boundary edges" % a)
            boundary_next[a] = c
    if sorted(boundary_next.keys()) != sorted(boundary_next.values()):
        fail(mesh, "boundary edges do not form closed loops")
    seen = set()
    loops = 0
    for start in sorted(boundary_next):
        if start in seen:
            continue
        loops += 1
        v = start
        while v not in seen:
            seen.add(v)
            v = boundary_next[v]
        if v != start:
            fail(mesh, "boundary walk from %d does not return" % start)
    # Components by union-find over edges.
    uf = UnionFind(nv)
    for (a, c) in undirected:
        uf.union(a, c)
    comp_of = [uf.find(v) for v in range(nv)]
    components = len(set(comp_of))

    chi = nv - ne + nf
    expected_chi = 2 * mesh.components - 2 * mesh.genus - mesh.boundary_loops
    if chi != expected_chi:
        fail(mesh, "V-E+F = %d but construction says 2c-2g-b = %d" % (chi, expected_chi))
    if loops != mesh.boundary_loops:
        fail(mesh, "walked %d boundary loops, construction says %d" % (loops, mesh.boundary_loops))
    if components != mesh.components:
        fail(mesh, "union-find found %d components, construction says %d" % (components, mesh.components))
    closed = loops == 0

    check_orientation(mesh, comp_of, closed)
    if mesh.face_groups is not None and len(mesh.face_groups) != len(mesh.faces):
        fail(mesh, "%d face groups for %d faces" % (len(mesh.face_groups), len(mesh.faces)))
    if mesh.periodic_square:
        check_periodic_square(mesh, boundary_next)

    # Valences (number of incident edges).
    valence = [0] * nv
    for (a, c) in undirected:
        valence[a] += 1
        valence[c] += 1
    on_boundary = set(boundary_next)
    for k in mesh.required_valences:
        if k not in valence:
            fail(mesh, "construction promises a vertex of valence %d" % k)
    degrees = [len(f) for f in mesh.faces]
    tris = all(d == 3 for d in degrees)
    quads = all(d == 4 for d in degrees)
    extraordinary = []
    if tris or quads:
        regular = 6 if tris else 4
        extraordinary = sorted(valence[v] for v in range(nv) if v not in on_boundary and valence[v] != regular)
    return {
        "V": nv, "E": ne, "F": nf, "chi": expected_chi, "closed": closed,
        "tris": tris, "quads": quads, "extraordinary": extraordinary,
        "degrees": degrees, "valence": valence, "boundary": on_boundary,
    }


def newell_normal(mesh, f):
    n = (0.0, 0.0, 0.0)
    for k in range(len(f)):
        n = vadd(n, cross(mesh.verts[f[k]], mesh.verts[f[(k + 1) % len(f)]]))
    return vscale(n, 0.5)


def check_orientation(mesh, comp_of, closed):
    for f in mesh.faces:
        if not norm(newell_normal(mesh, f)) > 1e-6:
            fail(mesh, "face %r is degenerate (no area)" % (f,))
    if mesh.orientation == "volume" and closed and mesh.genus == 0 and mesh.components == 1:
        # Genus-0 closed meshes here are star-shaped about the origin: every
        # face must also face away from it individually.
        for f in mesh.faces:
            c = (0.0, 0.0, 0.0)
            for v in f:
                c = vadd(c, mesh.verts[v])
            if not dot(newell_normal(mesh, f), c) > 1e-9:
                fail(mesh, "face %r faces the origin (not outward)" % (f,))
    if mesh.orientation == "volume":
        if not closed:
            fail(mesh, "volume orientation check needs a closed mesh")
        volume = {}
        for f in mesh.faces:
            p0 = mesh.verts[f[0]]
            for k in range(1, len(f) - 1):
                p1, p2 = mesh.verts[f[k]], mesh.verts[f[k + 1]]
                c = comp_of[f[0]]
                volume[c] = volume.get(c, 0.0) + dot(p0, cross(p1, p2)) / 6.0
        for c, vol in volume.items():
            if not vol > 1e-6:
                fail(mesh, "component of vertex %d has signed volume %r (not outward)" % (c, vol))
    elif mesh.orientation == "plus_z":
        for f in mesh.faces:
            if any(mesh.verts[v][2] != 0.0 for v in f):
                fail(mesh, "planar mesh has z != 0")
            area = 0.0
            for k in range(len(f)):
                p, q = mesh.verts[f[k]], mesh.verts[f[(k + 1) % len(f)]]
                area += p[0] * q[1] - q[0] * p[1]
            if not area > 1e-9:
                fail(mesh, "face %r is not counter-clockwise about +z" % (f,))
    elif mesh.orientation in ("radial_y", "radial_z", "radial_o"):
        # Away from the y or z axis, or from the origin.
        keep = {"radial_y": (1.0, 0.0, 1.0), "radial_z": (1.0, 1.0, 0.0), "radial_o": (1.0, 1.0, 1.0)}[mesh.orientation]
        for f in mesh.faces:
            c = (0.0, 0.0, 0.0)
            for v in f:
                c = vadd(c, mesh.verts[v])
            c = vscale(c, 1.0 / len(f))
            p0, p1, p2 = mesh.verts[f[0]], mesh.verts[f[1]], mesh.verts[f[2]]
            n = cross(vsub(p1, p0), vsub(p2, p0))
            if not dot(n, (c[0] * keep[0], c[1] * keep[1], c[2] * keep[2])) > 1e-9:
                fail(mesh, "face %r does not face outwards (%s)" % (f, mesh.orientation))
    else:
        fail(mesh, "unknown orientation check %r" % mesh.orientation)


def check_periodic_square(mesh, boundary_next):
    """Boundary vertices lie on the sides of [0 1]^2 with the same coordinates on opposite sides,
    the square's corners are vertices of one face each, every other vertex is inside, and every
    face is strictly convex and counter-clockwise (no fold-over of the control net)."""
    on_side = {"left": [], "right": [], "bottom": [], "top": []}
    for v in boundary_next:
        x, y, _ = mesh.verts[v]
        sides = [name for name, ok in (("left", x == 0.0), ("right", x == 1.0), ("bottom", y == 0.0),
                                       ("top", y == 1.0)) if ok]
        if not sides:
            fail(mesh, "boundary vertex %d at (%r, %r) is not on a side of the unit square" % (v, x, y))
        for name in sides:
            on_side[name].append(y if name in ("left", "right") else x)
    if sorted(on_side["left"]) != sorted(on_side["right"]):
        fail(mesh, "left and right sides do not match: %r vs %r" % (sorted(on_side["left"]), sorted(on_side["right"])))
    if sorted(on_side["bottom"]) != sorted(on_side["top"]):
        fail(mesh, "bottom and top sides do not match")
    for v, p in enumerate(mesh.verts):
        if not (0.0 <= p[0] <= 1.0 and 0.0 <= p[1] <= 1.0):
            fail(mesh, "vertex %d outside the unit square" % v)
    for corner in ((0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)):
        ids = [v for v, p in enumerate(mesh.verts) if (p[0], p[1]) == corner]
        if len(ids) != 1 or sum(1 for f in mesh.faces if ids[0] in f) != 1:
            fail(mesh, "square corner %r is not a vertex of exactly one face" % (corner,))
    for f in mesh.faces:
        for k in range(len(f)):
            a, b, c = mesh.verts[f[k - 1]], mesh.verts[f[k]], mesh.verts[f[(k + 1) % len(f)]]
            turn = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0])
            if not turn > 1e-9:
                fail(mesh, "face %r is not strictly convex at vertex %d" % (f, f[k]))


def corner_angles(mesh):
    """Smallest and largest interior angle (degrees) of the faces of a planar mesh."""
    angles = []
    for f in mesh.faces:
        for k in range(len(f)):
            a, b, c = mesh.verts[f[k - 1]], mesh.verts[f[k]], mesh.verts[f[(k + 1) % len(f)]]
            u, w = vsub(a, b), vsub(c, b)
            angles.append(math.degrees(math.acos(dot(u, w) / (norm(u) * norm(w)))))
    return min(angles), max(angles)


# --------------------------------------------------------------------------
# Output
# --------------------------------------------------------------------------

def obj_text(mesh):
    lines = ["# generated by %s \u2014 %s" % (SCRIPT, mesh.description)]
    for p in mesh.verts:
        lines.append("v %r %r %r" % p)
    for k, f in enumerate(mesh.faces):
        if mesh.face_groups is not None and (k == 0 or mesh.face_groups[k] != mesh.face_groups[k - 1]):
            lines.append("usemtl " + mesh.face_groups[k])
        lines.append("f " + " ".join(str(v + 1) for v in f))
    lines.extend(mesh.tags)
    return "\n".join(lines) + "\n"


def histogram(values):
    counts = {}
    for v in values:
        counts[v] = counts.get(v, 0) + 1
    return " ".join("%d\u00d7%d" % (k, counts[k]) for k in sorted(counts))


README_HEAD = """\
# Bundled example meshes

<!-- generated by tools/make_meshes.py; do not edit by hand -->

Every mesh here is generated by `tools/make_meshes.py` (Python standard library
only, deterministic). Do not edit these files: change the script and rerun
`python3 tools/make_meshes.py`; `python3 tools/make_meshes.py --check` verifies
that the committed files are reproducible. The same script writes the test
oracle `tests/data/bundled_meshes.csv` (read by `tests/support/mesh_zoo.h`).

Conventions: OBJ with `v x y z` (floats rounded to 12 decimals, written
round-trip exact) and 1-based `f` lines; every face is counter-clockwise seen
from outside (open planar meshes: normal +z). All meshes are consistently
oriented 2-manifolds (with boundary) without isolated vertices; the script
checks this, and that V - E + F = 2c - 2g - b, before writing anything.

Scale: the cube has edge 1; the tetrahedron, octahedron, icosahedron,
dodecahedron and all spheres have unit circumradius.

Plates (`limsurf plate`, docs/fem.md "Plates"), all of the square [0 10]^2:
`plate_sym` (fourfold symmetric; valences 3 and 5 inside) and `plate_flip` (no
symmetry; valences 3 and 5) stand in for the seed's Fig. 8 meshes, which the
paper shows only as pictures. They are placed by the paper's own numbers: the
verdicts of §4 depend on where a valence-5 vertex's limit point sits in the
exact solution, so `plate_sym`'s four lie where Navier's solution under the
sinusoidal load has the R = 29.2 of §4.2 (x = y = 1.786; the exact R there is
35, and 0.50 under the uniform load), and `plate_flip` has one in a cup of that
solution and one at its central saddle, as §4.3's P6 and P12.
`plate_ev35` (symmetric, valence-5 vertices at the quarter points) and
`plate_asym` (no symmetry; valences 3, 5 and 6 inside) were the earlier
stand-ins and stay as test meshes. Their boundary control points lie on the
square's edges, so the limit boundary is the square, and each square corner is
a corner of one face only (a corner shared by two faces converges only like h).
`plate_asym` is a partition of the square into a hexagon, three pentagons, a
quad and a triangle, each split into quads about its centroid through its edge
midpoints; the partition's corners were placed for the fine quads' angles
(35 to 146 degrees).

Periodic unit squares (plane elasticity with periodic conditions, the seed's
§6 block of material): `rve_block` and `square_inclusion` are planar control
meshes of [0 1]^2 whose boundary vertices lie on the sides, with the same
coordinates on opposite sides (left and right: the same y; bottom and top: the
same x), each square corner a valence-2 corner of one face, and only strictly
convex counter-clockwise faces (the script checks all of it). Their faces carry
material groups (`usemtl`, docs/io.md "Face groups"). `rve_block` (groups
`matrix`, `grain`) has interior valences 3, 5 and 6; the grains are the faces
around four of its vertices. `square_inclusion` (groups `matrix`, `inclusion`)
is an O-grid around a centred disc; its 24 interface edges are infinitely sharp
creases, so the interface is the closed cubic B-spline of its vertices, placed
on the radius R with (2 + cos 15°)/3 · R = 0.25: the limit interface passes
through radius 0.25 at its vertices (volume fraction about π/16 = 0.196).

Shells (`limsurf shell`, docs/fem.md "Shells", docs/guide/shell.md): the shell
obstacle course. `shell_scordelis_lo`, `shell_pinched_cylinder` and
`shell_hemisphere` are points of the exact surfaces (a cylindrical roof of
radius 25, a cylinder of radius 300, a hemisphere of radius 10 with an 18-degree
hole) on coarse grids whose load and probe points are vertices; use them with
`--surface` (or `--interpolate`), which fits the control points so that the
limit surface passes through them.

Columns: V, E, F; χ = V - E + F; g genus; b boundary loops; c components;
face degrees as `degree×count`; valences (edges per vertex) as
`valence×count`, interior and boundary vertices separately.

| file | what it is | V | E | F | χ | g | b | c | face degrees | interior valences | boundary valences |
|---|---|---|---|---|---|---|---|---|---|---|---|
"""


def readme_text(meshes, infos):
    lines = [README_HEAD.rstrip("\n")]
    for m, info in zip(meshes, infos):
        interior = [info["valence"][v] for v in range(info["V"]) if v not in info["boundary"]]
        boundary = [info["valence"][v] for v in range(info["V"]) if v in info["boundary"]]
        lines.append("| `%s.obj` | %s | %d | %d | %d | %d | %d | %d | %d | %s | %s | %s |" % (
            m.name, m.description, info["V"], info["E"], info["F"], info["chi"], m.genus,
            m.boundary_loops, m.components, histogram(info["degrees"]),
            histogram(interior) or "\u2013", histogram(boundary) or "\u2013"))
    return "\n".join(lines) + "\n"


def csv_text(meshes, infos):
    lines = [CSV_HEADER]
    for m, info in zip(meshes, infos):
        for bad in (",", '"', "\n"):
            if bad in m.description:
                fail(m, "description must not contain %r" % bad)
        lines.append(",".join([
            m.name, m.name + ".obj", str(info["V"]), str(info["E"]), str(info["F"]), str(info["chi"]),
            str(m.genus), str(m.boundary_loops), str(m.components),
            "1" if info["closed"] else "0", "1" if info["tris"] else "0", "1" if info["quads"] else "0",
            " ".join(str(v) for v in info["extraordinary"]), m.description,
        ]))
    return "\n".join(lines) + "\n"


def generate(root):
    """Build, check and write everything under root. Returns the meshes and infos."""
    meshes = all_meshes()
    names = [m.name for m in meshes]
    if len(set(names)) != len(names):
        raise MeshError("duplicate mesh names")
    infos = [analyse(m) for m in meshes]
    mesh_dir = os.path.join(root, MESH_SUBDIR)
    os.makedirs(mesh_dir, exist_ok=True)
    os.makedirs(os.path.dirname(os.path.join(root, CSV_PATH)), exist_ok=True)
    wanted = set()
    for m in meshes:
        path = os.path.join(mesh_dir, m.name + ".obj")
        wanted.add(m.name + ".obj")
        write(path, obj_text(m))
    # Remove stale generated meshes (only .obj files in data/meshes).
    for fname in sorted(os.listdir(mesh_dir)):
        if fname.endswith(".obj") and fname not in wanted:
            os.remove(os.path.join(mesh_dir, fname))
    write(os.path.join(mesh_dir, "README.md"), readme_text(meshes, infos))
    write(os.path.join(root, CSV_PATH), csv_text(meshes, infos))
    return meshes, infos


def write(path, text):
    with open(path, "w", encoding="utf-8", newline="\n") as fh:
        fh.write(text)


def check(root):
    """Regenerate into a temporary directory; return the list of differences."""
    problems = []
    with tempfile.TemporaryDirectory(prefix="limsurf-meshes-") as tmp:
        generate(tmp)
        fresh_dir = os.path.join(tmp, MESH_SUBDIR)
        have_dir = os.path.join(root, MESH_SUBDIR)
        fresh = set(os.listdir(fresh_dir))
        have = set(os.listdir(have_dir)) if os.path.isdir(have_dir) else set()
        for name in sorted(fresh - have):
            problems.append("missing: %s" % os.path.join(MESH_SUBDIR, name))
        for name in sorted(have - fresh):
            problems.append("not generated: %s" % os.path.join(MESH_SUBDIR, name))
        for name in sorted(fresh & have):
            if not filecmp.cmp(os.path.join(fresh_dir, name), os.path.join(have_dir, name), shallow=False):
                problems.append("differs: %s" % os.path.join(MESH_SUBDIR, name))
        fresh_csv = os.path.join(tmp, CSV_PATH)
        have_csv = os.path.join(root, CSV_PATH)
        if not os.path.isfile(have_csv):
            problems.append("missing: %s" % CSV_PATH)
        elif not filecmp.cmp(fresh_csv, have_csv, shallow=False):
            problems.append("differs: %s" % CSV_PATH)
    return problems


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true",
                        help="regenerate into a temporary directory and fail if the committed files differ")
    parser.add_argument("--root", default=ROOT, help="repository root (default: the script's parent)")
    args = parser.parse_args(argv)
    try:
        if args.check:
            problems = check(args.root)
            if problems:
                for p in problems:
                    print("make_meshes --check: " + p, file=sys.stderr)
                print("make_meshes --check: FAILED; rerun python3 tools/make_meshes.py", file=sys.stderr)
                return 1
            print("make_meshes --check: data/meshes and %s are up to date" % CSV_PATH)
            return 0
        meshes, _ = generate(args.root)
        print("make_meshes: wrote %d meshes to %s and %s" % (len(meshes), MESH_SUBDIR, CSV_PATH))
        return 0
    except MeshError as exc:
        print("make_meshes: self-check FAILED: %s" % exc, file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
