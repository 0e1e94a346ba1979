#pragma once
// The C entry points of libowsim_mesh.so (io/scenario/mesh/mesh_module.cpp), the optional module
// that reads triangle meshes (OBJ with tinyobjloader, other formats with assimp). The loader (io/scenario/mesh_file.cpp) refuses a module
// whose owsim_mesh_module_abi() differs from OWSIM_MESH_MODULE_ABI.
#include <cstddef>

#define OWSIM_MESH_MODULE_ABI 2

extern "C" {

// Receives the mesh read (called once, before owsim_mesh_read returns 0): vertex_count vertices
// of 3 doubles (the file's own coordinates, every node's transformation applied) and
// triangle_count triangles of 3 vertex indices, in the file's winding.
typedef void (*owsim_mesh_sink)(void* context, std::size_t vertex_count, const double* xyz,
                                std::size_t triangle_count, const unsigned* corners);

// Receives, once each, every file the model file made the reader open besides itself (an OBJ's
// material library, a glTF's buffers), as canonical paths: all beside or below the model file.
typedef void (*owsim_mesh_file_sink)(void* context, const char* path);

typedef int (*owsim_mesh_module_abi_fn)(void);
// Reads every mesh of the model file at `path` (OBJ, PLY, or any format assimp reads), polygons
// split into triangles, points and lines left out. Returns 0 and calls `sink` once (and
// `file_sink` for each other file read), or returns non-zero with a one-line message in `error`.
// The file may only make the reader open regular files in its own folder's tree: any other name
// it holds (an absolute path elsewhere, "..", a device) is refused and the read fails.
typedef int (*owsim_mesh_read_fn)(const char* path, owsim_mesh_sink sink,
                                  owsim_mesh_file_sink file_sink, void* sink_context, char* error,
                                  std::size_t error_size);
}
