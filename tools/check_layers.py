#!/usr/bin/env python3
"""Checks the layering of limsurf's sources (docs/coding_style.md, "Layout").

Each layer may include only itself and the layers it stands on. The rule is
read from LAYERS below; a violation prints "file:line: <layer> may not include
<other layer>" and the script exits 1. Run by CTest (test layers.include_rules).
"""
import pathlib
import re
import sys

# layer -> layers it may include (besides itself)
LAYERS = {
    "core": set(),
    "mesh": {"core"},
    "io": {"core", "mesh"},
    "scheme": {"core", "mesh"},
    "refine": {"core", "mesh", "scheme"},
    "limit": {"core", "mesh", "scheme", "refine"},
    "quadrature": {"core", "mesh", "scheme", "refine", "limit"},
    "volume": {"core", "mesh", "scheme", "refine"},
    "sec": {"core", "mesh", "scheme", "refine", "limit", "quadrature"},
    "analysis": {"core", "mesh", "scheme", "refine", "limit", "quadrature"},
    "fem": {"core", "mesh", "scheme", "refine", "limit", "quadrature"},
    "render": {"core", "mesh", "io", "scheme", "refine", "limit", "quadrature"},
    "membrane": {"core", "mesh", "scheme", "refine", "limit", "quadrature", "volume"},
    # drivers shared by the CLI and the Python module: may stand on every library layer
    "apps": {"core", "mesh", "io", "scheme", "refine", "limit", "quadrature", "volume", "sec", "analysis", "fem",
             "render", "membrane"},
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"limsurf/([a-z_]+)/')


def layer_of(path, root):
    parts = path.relative_to(root).parts
    # include/limsurf/<layer>/x.h or src/limsurf/<layer>/x.cpp; src/limsurf/detail is shared privately
    if len(parts) >= 4 and parts[1] == "limsurf" and parts[2] in LAYERS:
        return parts[2]
    return None


# The front ends stand on the library's public headers only: the CLI (cli/) and the Python module
# (python/src/) may include any layer's include/limsurf/<layer>/ header, never src/limsurf/detail,
# and the library never includes a front end (pybind11, CLI11).
FRONT_ENDS = ("cli", "python/src")
FRONT_END_INCLUDE = re.compile(r'^\s*#\s*include\s+[<"](pybind11/|CLI/|commands/)')


def front_end_problems(root):
    problems = []
    for front_end in FRONT_ENDS:
        for path in sorted((root / front_end).rglob("*.[ch]*")):
            for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
                match = INCLUDE.match(line)
                if match and match.group(1) == "detail":
                    problems.append("%s:%d: a front end may include public headers only, not limsurf/detail"
                                    % (path.relative_to(root), number))
    for path in sorted(list((root / "include").rglob("*.h")) + list((root / "src").rglob("*.[ch]*"))):
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
            if FRONT_END_INCLUDE.match(line):
                problems.append("%s:%d: the library may not include a front end" % (path.relative_to(root), number))
    return problems


def main():
    root = pathlib.Path(__file__).resolve().parent.parent
    problems = []
    files = sorted(list((root / "include" / "limsurf").rglob("*.h")) + list((root / "src" / "limsurf").rglob("*.[ch]pp"))
                   + list((root / "src" / "limsurf").rglob("*.h")))
    unknown = sorted({p.relative_to(root).parts[2] for p in files
                      if len(p.relative_to(root).parts) >= 4 and p.relative_to(root).parts[2] not in LAYERS
                      and p.relative_to(root).parts[2] != "detail"})
    for name in unknown:
        problems.append("layer '%s' is not in tools/check_layers.py LAYERS: add its rule" % name)
    for path in files:
        layer = layer_of(path, root)
        if layer is None:
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
            match = INCLUDE.match(line)
            if not match or match.group(1) == layer or match.group(1) in LAYERS[layer]:
                continue
            # private helpers (src/limsurf/detail) serve every layer's sources, never public headers
            if match.group(1) != "detail" or path.relative_to(root).parts[0] != "src":
                problems.append("%s:%d: %s may not include %s" % (path.relative_to(root), number, layer,
                                                                  match.group(1)))
    problems += front_end_problems(root)
    for problem in problems:
        print(problem, file=sys.stderr)
    if not problems:
        print("check_layers: %d files follow the layering" % len(files))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
