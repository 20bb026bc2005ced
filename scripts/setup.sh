#!/usr/bin/env bash
# Installs every Debian package limsurf needs to build, test and run its demo.
# Idempotent: installs only what is missing, and runs `apt-get update` only
# when the package lists are missing or an install from them fails.
# Works as root or through sudo. Usage: scripts/setup.sh [--fuzz]
set -euo pipefail

packages=(
    # toolchain
    cmake g++ make pkg-config
    # library (SuiteSparse: CHOLMOD for the sec layer's sparse Cholesky); OpenBLAS (serial: no
    # threads of its own, the same bits on every run) in place of the reference BLAS that CHOLMOD's
    # supernodal factorisations and solves would otherwise call (docs/BENCHMARKS.md: 2-3x on SEC)
    libeigen3-dev libsuitesparse-dev libopenblas0-serial
    # command-line tool (muParser: formula right-hand sides of limsurf poisson)
    libcli11-dev nlohmann-json3-dev libmuparser-dev
    # volume-form generator and its tests: exact rationals (GMP through Boost.Multiprecision)
    libgmp-dev
    # tests and benchmarks
    libgtest-dev libgmock-dev libbenchmark-dev
    # peers: tests and benchmarks (OpenSubdiv, CGAL with Boost headers, OpenMesh)
    libosd-dev libcgal-dev libboost-dev libopenmesh-dev
    # test-only peer: an independent OBJ reader
    libtinyobjloader-dev
    # bundled-mesh reproducibility test (tools/make_meshes.py --check)
    python3
    # pictures: PNG writing (stb_image_write) for limsurf render
    libstb-dev
    # the Python module (pybind11 against Debian's python3 with numpy and scipy) and its tests,
    # the studies' plots (matplotlib)
    python3-dev pybind11-dev python3-pybind11 python3-numpy python3-scipy python3-pytest python3-matplotlib
    # test-only peer: an independent glTF reader (tinygltf) for the .glb export
    libtinygltf-dev
    # SEC applications: Spectra's eigensolvers (spectral conformal parameterisation)
    libspectra-dev
    # biomembranes: Ipopt for the constrained shape optimisation; Surface Evolver as a test-only peer
    coinor-libipopt-dev evolver
    # plane elasticity: FreeFem++ as a test-only peer (body-fitted P2 homogenisation of the cell)
    freefem++
    # test-only: qemu-user runs the kernels' SSE2 and AVX2 copies on any x86-64 machine
    # (tests/membrane/same_bits_on_every_cpu.cmake)
    qemu-user
)

# `setup.sh --fuzz` adds what the libFuzzer targets need (make fuzz).
if [ "${1:-}" = "--fuzz" ]; then
    packages+=(clang libclang-rt-14-dev)
fi

missing=()
for package in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$package")
    fi
done
if [ ${#missing[@]} -eq 0 ]; then
    exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
    as_root=()
elif command -v sudo >/dev/null 2>&1; then
    as_root=(sudo)
else
    echo "error: missing packages (${missing[*]}) and neither root nor sudo to install them" >&2
    exit 1
fi

export DEBIAN_FRONTEND=noninteractive
echo "setup: installing ${missing[*]}" >&2
lists_present() { compgen -G "/var/lib/apt/lists/*_Packages*" >/dev/null; }
if ! lists_present; then
    "${as_root[@]}" apt-get update -qq
fi
if ! "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null; then
    # The lists may be stale (a package version no longer served): refresh once and retry.
    "${as_root[@]}" apt-get update -qq
    "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
