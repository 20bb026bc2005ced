#!/usr/bin/env python3
"""Extracts OpenSubdiv's regression shapes (regression/shapes/*.h) into OBJ files.

OpenSubdiv keeps its regression suite as C++ headers, one string constant per
shape (`static const std::string catmark_cube = "v ...\\n" "f ...\\n" ...;`).
This script reads those headers from a checkout or from a git directory without
a work tree (at a given revision), undoes the C string escapes and writes
`<name>.obj` into the output folder, each starting with a comment that names
its origin (repository, commit, path), its copyright line and licence, and the
scheme OpenSubdiv's regression runs it under (the name's prefix: catmark,
loop, bilinear). The shape text itself is written unchanged, so OpenSubdiv's
tags (`t crease ...`, `t interpolateboundary ...`) come along.

    python3 tools/extract_opensubdiv_shapes.py /path/to/OpenSubdiv tests/data/opensubdiv_shapes
    python3 tools/extract_opensubdiv_shapes.py --git-dir /path/repo.git --rev HEAD OUT

`--check` compares instead of writing and exits 1 when a file would change.
Standard library only.
"""
import argparse
import pathlib
import re
import subprocess
import sys

SHAPES = "regression/shapes"
REPOSITORY = "https://github.com/PixarAnimationStudios/OpenSubdiv"
SCHEMES = {"catmark": "catmull-clark", "loop": "loop", "bilinear": "bilinear"}

DECLARATION = re.compile(r"static\s+const\s+std::string\s+(\w+)\s*=(.*?);", re.S)
LITERAL = re.compile(r'"((?:[^"\\]|\\.)*)"', re.S)
ESCAPES = {"n": "\n", "t": "\t", '"': '"', "\\": "\\", "'": "'", "r": "\r"}


class Source:
    """Reads files under regression/shapes from a checkout or a git directory."""

    def __init__(self, root, git_dir, rev):
        self.root = pathlib.Path(root) if root else None
        self.git_dir = git_dir
        self.rev = rev

    def git(self, *args):
        return subprocess.run(["git", "--git-dir", self.git_dir, *args], check=True, capture_output=True,
                              text=True).stdout

    def commit(self):
        if self.git_dir:
            return self.git("rev-parse", self.rev).strip()
        try:
            return subprocess.run(["git", "-C", str(self.root), "rev-parse", "HEAD"], check=True,
                                  capture_output=True, text=True).stdout.strip()
        except (subprocess.CalledProcessError, FileNotFoundError):
            return "unknown (not a git checkout)"

    def headers(self):
        if self.git_dir:
            names = self.git("ls-tree", "--name-only", f"{self.rev}:{SHAPES}").split()
        else:
            names = [p.name for p in (self.root / SHAPES).iterdir()]
        return sorted(n for n in names if n.endswith(".h") and n != "all.h")

    def read(self, name):
        if self.git_dir:
            return self.git("show", f"{self.rev}:{SHAPES}/{name}")
        return (self.root / SHAPES / name).read_text()


def unescape(literal):
    out, i = [], 0
    while i < len(literal):
        c = literal[i]
        if c == "\\" and i + 1 < len(literal):
            nxt = literal[i + 1]
            if nxt not in ESCAPES:
                raise ValueError(f"unsupported escape \\{nxt}")
            out.append(ESCAPES[nxt])
            i += 2
        else:
            out.append(c)
            i += 1
    return "".join(out)


def parse_header(text, header):
    """(name, shape text, copyright line) of the one shape in a header."""
    found = DECLARATION.findall(text)
    if len(found) != 1:
        raise ValueError(f"{header}: expected one shape string, found {len(found)}")
    name, body = found[0]
    shape = "".join(unescape(s) for s in LITERAL.findall(body))
    copyright_lines = [ln.strip("/ ").strip() for ln in text.splitlines() if "Copyright" in ln]
    return name, shape, copyright_lines[0] if copyright_lines else "no copyright line"


def obj_text(name, shape, copyright_line, commit):
    prefix = name.split("_")[0]
    if prefix not in SCHEMES:
        raise ValueError(f"{name}: unknown scheme prefix '{prefix}'")
    header = [
        f"# OpenSubdiv regression shape '{name}', extracted by tools/extract_opensubdiv_shapes.py",
        f"# from {REPOSITORY} {SHAPES}/{name}.h at commit {commit}.",
        f"# {copyright_line.rstrip('.')}; licensed under the modified Apache License 2.0 in LICENSE.txt",
        "# beside this file. The shape text below is OpenSubdiv's, unchanged.",
        f"# scheme: {SCHEMES[prefix]}",
    ]
    return "\n".join(header) + "\n" + shape


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("checkout", nargs="?", help="OpenSubdiv source checkout (omit with --git-dir)")
    parser.add_argument("output", help="folder for the OBJ files")
    parser.add_argument("--git-dir", help="OpenSubdiv git directory (read without a work tree)")
    parser.add_argument("--rev", default="HEAD", help="revision to read with --git-dir (default HEAD)")
    parser.add_argument("--check", action="store_true", help="compare with the folder instead of writing")
    args = parser.parse_args()
    if bool(args.checkout) == bool(args.git_dir):
        parser.error("give either a checkout or --git-dir")
    source = Source(args.checkout, args.git_dir, args.rev)
    commit = source.commit()
    out = pathlib.Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    changed = []
    for header in source.headers():
        name, shape, copyright_line = parse_header(source.read(header), header)
        path = out / f"{name}.obj"
        text = obj_text(name, shape, copyright_line, commit)
        if args.check:
            if not path.exists() or path.read_text() != text:
                changed.append(path.name)
        else:
            path.write_text(text)
    if args.check and changed:
        print("would change: " + " ".join(changed), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
