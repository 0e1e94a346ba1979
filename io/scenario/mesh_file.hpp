#pragma once
// Triangle meshes from model files (scenario key meshes, ../shared/INTERFACE.md "Real-world
// scenes"): OBJ (tinyobjloader, double precision), PLY or any format assimp reads, through the
// optional module libowsim_mesh.so. The vertices are the file's own coordinates in metres (float
// precision in assimp: keep a model's coordinates local, not UTM), every node's transformation
// applied.
#include <filesystem>
#include <vector>

#include "geometry/triangle_mesh.hpp"

namespace owsim {

struct MeshFile {
  TriangleMesh mesh;
  // The other files reading it opened (an OBJ's material library, a glTF's buffers): canonical,
  // all beside or below the model file, which may make the reader open nothing else.
  std::vector<std::filesystem::path> companions;
};

// Throws owsim::Error "<file>: <problem>" (the module missing, a file assimp cannot read, a model
// without triangles, a model naming a file outside its folder's tree or not a regular file).
[[nodiscard]] MeshFile read_mesh_file(const std::filesystem::path& file);

}  // namespace owsim
