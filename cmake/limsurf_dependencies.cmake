# Every dependency is a Debian package installed by scripts/setup.sh;
# find_package only: no downloads, no vendored code.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
# Spectra (libspectra-dev): header-only eigensolvers for the apps layer (spectral conformal
# parameterisation, harmonic forms), used privately.
find_package(spectra 1.0 REQUIRED CONFIG)
set_package_properties(Eigen3 PROPERTIES TYPE REQUIRED PURPOSE "dense and sparse linear algebra (libeigen3-dev)")

if(LIMSURF_BUILD_CLI)
    find_package(CLI11 REQUIRED)
    set_package_properties(CLI11 PROPERTIES TYPE REQUIRED PURPOSE "command-line parsing (libcli11-dev)")
    find_package(nlohmann_json 3 REQUIRED)
    set_package_properties(nlohmann_json PROPERTIES TYPE REQUIRED PURPOSE "--json output (nlohmann-json3-dev)")
endif()

if(LIMSURF_BUILD_TESTS)
    find_package(GTest REQUIRED)
    set_package_properties(GTest PROPERTIES TYPE REQUIRED PURPOSE "unit tests (libgtest-dev)")
    # tinyobjloader is a test-only peer: an independent OBJ reader to check ours against.
    # Required, so that the witness cannot silently vanish (scripts/setup.sh installs it).
    find_package(tinyobjloader REQUIRED)
    set_package_properties(tinyobjloader PROPERTIES TYPE REQUIRED PURPOSE "peer OBJ reader in tests (libtinyobjloader-dev)")
endif()

# GMP (exact rationals and long floats, through Boost.Multiprecision's GMP back end) for the
# volume-form generator and its tests; the library itself needs neither.
if(LIMSURF_BUILD_TOOLS OR LIMSURF_BUILD_TESTS)
    find_package(Boost 1.74 REQUIRED)
    set_package_properties(Boost PROPERTIES TYPE REQUIRED PURPOSE "Boost.Multiprecision for the volume-form generator (libboost-dev)")
    find_path(GMP_INCLUDE_DIR gmp.h)
    find_library(GMP_LIBRARY gmp)
    if(NOT GMP_INCLUDE_DIR OR NOT GMP_LIBRARY)
        message(FATAL_ERROR "GMP not found: install libgmp-dev (scripts/setup.sh), or configure with "
                            "-DLIMSURF_BUILD_TOOLS=OFF -DLIMSURF_BUILD_TESTS=OFF")
    endif()
    add_library(limsurf_gmp INTERFACE IMPORTED)
    target_include_directories(limsurf_gmp SYSTEM INTERFACE ${GMP_INCLUDE_DIR})
    target_link_libraries(limsurf_gmp INTERFACE ${GMP_LIBRARY} Boost::headers)
    add_library(limsurf::gmp ALIAS limsurf_gmp)
    add_feature_info(gmp GMP_LIBRARY "GMP for the volume-form generator (libgmp-dev)")
endif()

# Peers for tests and benchmarks. Debian's OpenSubdivConfig.cmake references
# static libraries the package does not ship, so locate the headers and the
# CPU library directly and wrap them in an imported target.
if(LIMSURF_BUILD_TESTS OR LIMSURF_BUILD_BENCH)
    find_path(OPENSUBDIV_INCLUDE_DIR opensubdiv/far/topologyRefiner.h)
    find_library(OPENSUBDIV_CPU_LIBRARY osdCPU)
    if(OPENSUBDIV_INCLUDE_DIR AND OPENSUBDIV_CPU_LIBRARY)
        add_library(limsurf_peer_opensubdiv INTERFACE IMPORTED)
        target_include_directories(limsurf_peer_opensubdiv SYSTEM INTERFACE ${OPENSUBDIV_INCLUDE_DIR})
        target_link_libraries(limsurf_peer_opensubdiv INTERFACE ${OPENSUBDIV_CPU_LIBRARY})
        add_library(limsurf::peer_opensubdiv ALIAS limsurf_peer_opensubdiv)
    endif()
    add_feature_info(opensubdiv_peer OPENSUBDIV_CPU_LIBRARY "OpenSubdiv Far as a peer (libosd-dev)")
endif()
# CGAL (a test and benchmark peer) warns about Debug builds at the end of the
# top-level configuration; our Debug and sanitizer builds are deliberate.
set(CGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE TRUE)

# SuiteSparse's CHOLMOD for the sparse Cholesky factorisations of the sec layer (Poisson, inverse
# inner products). Optional: without it Eigen's SimplicialLDLT is used (same results, slower on
# large meshes). scripts/setup.sh installs libsuitesparse-dev.
option(LIMSURF_WITH_CHOLMOD "Use CHOLMOD (SuiteSparse) for sparse Cholesky when installed" ON)
if(LIMSURF_WITH_CHOLMOD)
    find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
    find_library(CHOLMOD_LIBRARY cholmod)
endif()
add_feature_info(cholmod CHOLMOD_LIBRARY "CHOLMOD sparse Cholesky for the sec layer (libsuitesparse-dev)")

# Ipopt (coinor-libipopt-dev): the interior-point NLP solver of the membrane layer's constrained
# shape optimisation (limsurf membrane). Optional: without it minimize_membrane() throws
# UnsupportedError; scripts/setup.sh installs it. Found through its pkg-config file.
option(LIMSURF_WITH_IPOPT "Use Ipopt for the membrane problems when installed" ON)
if(LIMSURF_WITH_IPOPT)
    find_package(PkgConfig QUIET)
    if(PKG_CONFIG_FOUND)
        pkg_check_modules(IPOPT QUIET IMPORTED_TARGET ipopt)
    endif()
endif()
add_feature_info(ipopt IPOPT_FOUND "Ipopt for the membrane problems (coinor-libipopt-dev)")

# muParser: right-hand sides from formulas in the CLI (limsurf poisson --rhs).
if(LIMSURF_BUILD_CLI)
    find_path(MUPARSER_INCLUDE_DIR muParser.h PATH_SUFFIXES muParser)
    find_library(MUPARSER_LIBRARY muparser)
    if(NOT MUPARSER_INCLUDE_DIR OR NOT MUPARSER_LIBRARY)
        message(FATAL_ERROR "muParser not found: install libmuparser-dev (scripts/setup.sh), or configure with "
                            "-DLIMSURF_BUILD_CLI=OFF")
    endif()
    add_library(limsurf_muparser INTERFACE IMPORTED)
    target_include_directories(limsurf_muparser SYSTEM INTERFACE ${MUPARSER_INCLUDE_DIR})
    target_link_libraries(limsurf_muparser INTERFACE ${MUPARSER_LIBRARY})
    add_library(limsurf::muparser ALIAS limsurf_muparser)
    add_feature_info(muparser MUPARSER_LIBRARY "formula right-hand sides in the CLI (libmuparser-dev)")
endif()
