// antcd/load.hpp — reading mesh files (OBJ, STL, PLY, OFF, glTF and the other formats assimp
// reads) into a Mesh. Part of the antcd::io library (link antcd::io; it links the core, and uses
// assimp and tinyobjloader privately): the core library antcd::antcd reads no mesh file (it reads
// and writes only its own model files, Model::load and Model::save, through antcd/file.hpp).
// Thread safety: load_mesh may be called from several threads at once (each call has its own
// importer).
#pragma once

#include <antcd/io_export.hpp>
#include <antcd/mesh.hpp>

#include <filesystem>

namespace antcd {

/// Loads every triangle of every mesh in a file (OBJ, STL ASCII/binary, PLY, OFF, glTF/GLB and the
/// other formats assimp reads), with node transforms of the file's scene graph applied, polygons
/// triangulated and identical vertices joined. Points and lines are ignored. A model file
/// (is_model_path: ".antcd", written by Model::save) gives the saved model's mesh, bit for bit.
/// Precision: OBJ, OFF and PLY (ASCII, and binary little-endian doubles) coordinates are the
/// nearest doubles to the file's text (a binary double bit for bit); OFF/PLY layouts the loader
/// does not follow, and the other formats, are read by assimp in single precision
/// (docs/guarantees.md).
/// Throws MeshError (naming the path) when the file is missing, is not a readable mesh, holds no
/// triangle, has non-finite coordinates or out-of-range indices.
ANTCD_IO_API Mesh load_mesh(const std::filesystem::path& path);

}  // namespace antcd
