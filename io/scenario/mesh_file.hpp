#pragma once
// Triangle meshes from model files (scenario key meshes, ../shared/INTERFACE.md "Real-world
// scenes"): OBJ, PLY or any format assimp reads, through the optional module libowsim_mesh.so.
// The vertices are the file's own coordinates in metres (float precision in assimp: keep a
// model's coordinates local, not UTM), every node's transformation applied.
#include <filesystem>

#include "geometry/triangle_mesh.hpp"

namespace owsim {

// Throws owsim::Error "<file>: <problem>" (the module missing, a file assimp cannot read, a model
// without triangles).
[[nodiscard]] TriangleMesh read_mesh_file(const std::filesystem::path& file);

}  // namespace owsim
