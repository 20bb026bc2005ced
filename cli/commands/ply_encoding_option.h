// --ply-encoding for the commands that write meshes (convert, subdivide).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/ply.h"

namespace limsurf::cli {

/// Registers `--ply-encoding ascii|binary-le|binary-be` (default ascii) on @p cmd.
inline void add_ply_encoding_option(CLI::App* cmd, std::string& name) {
    cmd->add_option("--ply-encoding", name,
                    "PLY encoding: ascii (default), binary-le or binary-be (binary: exact doubles, several times "
                    "smaller and faster to write)")
        ->check(CLI::IsMember({"ascii", "binary-le", "binary-be"}));
}

/// The encoding a checked --ply-encoding value names (empty, not given: ascii).
/// @throws InputError when it was given for an output that is not PLY (it would be ignored)
[[nodiscard]] inline PlyEncoding ply_encoding_from(const std::string& name, MeshFormat format) {
    LIMSURF_CHECK(name.empty() || format == MeshFormat::Ply, InputError, "--ply-encoding ", name,
                  " applies to PLY output only, and the output is ", format == MeshFormat::Obj ? "OBJ" : "OFF");
    return name == "binary-le"   ? PlyEncoding::BinaryLittleEndian
           : name == "binary-be" ? PlyEncoding::BinaryBigEndian
                                 : PlyEncoding::Ascii;
}

}  // namespace limsurf::cli
