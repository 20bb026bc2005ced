# Every dependency is a Debian package installed by scripts/setup.sh;
# find_package only: no downloads, no vendored code.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
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
