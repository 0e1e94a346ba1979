#include "io/scenario/mesh_file.hpp"

#include <array>
#include <string>

#include "geometry/error.hpp"
#include "io/files/optional_module.hpp"
#include "io/scenario/mesh_module_abi.hpp"

namespace owsim {
namespace {

void receive_mesh(void* context, std::size_t vertex_count, const double* xyz,
                  std::size_t triangle_count, const unsigned* corners) {
  TriangleMesh* mesh = &static_cast<MeshFile*>(context)->mesh;
  mesh->vertices.resize(vertex_count);
  for (std::size_t v = 0; v < vertex_count; ++v) {
    mesh->vertices[v] = {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]};
  }
  mesh->triangles.resize(triangle_count);
  for (std::size_t t = 0; t < triangle_count; ++t) {
    mesh->triangles[t] = {corners[3 * t], corners[3 * t + 1], corners[3 * t + 2]};
  }
}

void receive_companion(void* context, const char* path) {
  static_cast<MeshFile*>(context)->companions.emplace_back(path);
}

}  // namespace

MeshFile read_mesh_file(const std::filesystem::path& file) {
  const OptionalModule& module =
      OptionalModule::get("mesh", "triangle meshes (meshes)", OWSIM_MESH_MODULE_ABI);
  const auto read = reinterpret_cast<owsim_mesh_read_fn>(module.symbol("owsim_mesh_read"));
  MeshFile mesh;
  std::array<char, 1024> error{};
  if (read(file.c_str(), receive_mesh, receive_companion, &mesh, error.data(), error.size()) != 0) {
    throw Error(file.string() + ": " + error.data());
  }
  if (mesh.mesh.triangles.empty()) throw Error(file.string() + ": the mesh has no triangles");
  return mesh;
}

}  // namespace owsim
