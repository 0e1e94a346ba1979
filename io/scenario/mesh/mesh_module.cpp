// libowsim_mesh.so: the one place owsim touches assimp. Loaded on demand by
// io/scenario/mesh_file.cpp when a scenario places meshes, so that the owsim executable,
// libowsim_c.so and the Python module never map assimp and the library tree behind it. The entry
// points are plain C: no exception crosses them.
//
// Every mesh of the file is taken with its node's transformation applied (assimp's
// PreTransformVertices), polygons split into triangles; the coordinates are the file's own (no
// axis conversion: io/scenario/mesh_file.hpp says which axis is up).
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "io/scenario/mesh_module_abi.hpp"

namespace {

void copy_error(const std::string& message, char* error, std::size_t error_size) {
  if (error == nullptr || error_size == 0) return;
  std::snprintf(error, error_size, "%s", message.c_str());
}

// The first line of assimp's message, without the trailing newline it may carry.
std::string first_line(const char* text) {
  std::string line = text != nullptr ? text : "";
  line = line.substr(0, line.find('\n'));
  return line.empty() ? "unknown reason" : line;
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) int owsim_mesh_module_abi(void) {
  return OWSIM_MESH_MODULE_ABI;
}

__attribute__((visibility("default"))) int owsim_mesh_read(const char* path, owsim_mesh_sink sink,
                                                           void* sink_context, char* error,
                                                           std::size_t error_size) {
  try {
    Assimp::Importer importer;
    // Points and lines stay in the meshes and are skipped below: only triangles reach the sink.
    const aiScene* scene =
        importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                    aiProcess_PreTransformVertices);
    if (scene == nullptr) {
      copy_error("cannot read the mesh: " + first_line(importer.GetErrorString()), error,
                 error_size);
      return 1;
    }
    std::vector<double> xyz;
    std::vector<unsigned> corners;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
      const aiMesh* mesh = scene->mMeshes[m];
      const auto first = static_cast<unsigned>(xyz.size() / 3);
      for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
        const aiVector3D& vertex = mesh->mVertices[v];
        xyz.insert(xyz.end(), {static_cast<double>(vertex.x), static_cast<double>(vertex.y),
                               static_cast<double>(vertex.z)});
      }
      for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
        const aiFace& face = mesh->mFaces[f];
        if (face.mNumIndices != 3) continue;
        for (unsigned c = 0; c < 3; ++c) corners.push_back(first + face.mIndices[c]);
      }
    }
    sink(sink_context, xyz.size() / 3, xyz.data(), corners.size() / 3, corners.data());
    return 0;
  } catch (const std::exception& e) {
    copy_error(std::string("cannot read the mesh: ") + e.what(), error, error_size);
  } catch (...) {
    copy_error("cannot read the mesh: unknown error", error, error_size);
  }
  return 1;
}
}
