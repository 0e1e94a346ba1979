// libowsim_mesh.so: the one place owsim touches assimp. Loaded on demand by
// io/scenario/mesh_file.cpp when a scenario places meshes, so that the owsim executable,
// libowsim_c.so and the Python module never map assimp and the library tree behind it. The entry
// points are plain C: no exception crosses them.
//
// Every mesh of the file is taken with its node's transformation applied (assimp's
// PreTransformVertices), polygons split into triangles; the coordinates are the file's own (no
// axis conversion: io/scenario/mesh_file.hpp says which axis is up).
#include <assimp/DefaultIOSystem.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <new>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <system_error>
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

// assimp's file access confined to the model file's folder tree (issue 33): a name that resolves
// (symbolic links followed) elsewhere, or to anything but a regular file, is not opened — the read
// then fails naming it. Every file opened is kept, so a run folder can copy the model with them.
class ConfinedIOSystem : public Assimp::DefaultIOSystem {
 public:
  explicit ConfinedIOSystem(const std::filesystem::path& model) {
    std::error_code error;
    root_ =
        std::filesystem::canonical(model.parent_path().empty() ? "." : model.parent_path(), error);
    model_ = std::filesystem::canonical(model, error);  // empty when it cannot be resolved
  }

  bool Exists(const char* file) const override { return allowed(file).has_value(); }

  Assimp::IOStream* Open(const char* file, const char* mode) override {
    const bool reading = std::strpbrk(mode, "wa+") == nullptr;
    const std::optional<std::filesystem::path> path = allowed(file);
    if (!reading || !path) {
      if (refused_.empty()) refused_ = file;
      return nullptr;
    }
    if (*path != model_) opened_.insert(path->string());  // no exception through assimp
    return DefaultIOSystem::Open(path->c_str(), mode);
  }

  [[nodiscard]] const std::string& refused() const { return refused_; }
  [[nodiscard]] const std::set<std::string>& opened() const { return opened_; }

 private:
  std::optional<std::filesystem::path> allowed(const char* file) const {
    std::error_code error;
    const std::filesystem::path real = std::filesystem::canonical(file, error);
    if (error || root_.empty() || !std::filesystem::is_regular_file(real, error)) return {};
    const std::filesystem::path relative = real.lexically_relative(root_);
    if (relative.empty() || *relative.begin() == "..") return {};
    return real;
  }

  std::filesystem::path model_;
  std::filesystem::path root_;
  std::string refused_;
  std::set<std::string> opened_;
};

// A PLY header's element counts against the file's size, before assimp reserves them (a header
// claiming 4·10⁹ faces in a 200-byte file ran out of memory): every element takes at least 2
// bytes in ASCII (a digit and a line end) and its fixed-size properties' bytes in binary (a list
// at least its count's size). Returns the problem, or "" when the counts can fit.
std::string ply_counts_problem(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::string line;
  if (!std::getline(file, line) || line.rfind("ply", 0) != 0) return "";  // not a PLY
  const auto property_bytes = [](const std::string& type) -> double {
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
    if (type == "double" || type == "float64") return 8;
    return 4;
  };
  bool ascii = true;
  double least_bytes = 0.0;
  double count = 0.0;
  double element_bytes = 0.0;
  std::string claims;
  const auto close_element = [&] {
    least_bytes += count * (ascii ? 2.0 : std::max(1.0, element_bytes));
  };
  for (int lines = 0; lines < 10'000 && std::getline(file, line); ++lines) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "format") {
      std::string format;
      words >> format;
      ascii = format == "ascii";
    } else if (keyword == "element") {
      close_element();
      std::string name;
      words >> name >> count;
      element_bytes = 0.0;
      claims +=
          (claims.empty() ? "" : ", ") + std::to_string(static_cast<long long>(count)) + " " + name;
    } else if (keyword == "property") {
      std::string type;
      words >> type;
      element_bytes +=
          type == "list" ? (words >> type, property_bytes(type)) : property_bytes(type);
    } else if (keyword == "end_header") {
      break;
    }
  }
  close_element();
  std::error_code error;
  const auto size = static_cast<double>(std::filesystem::file_size(path, error));
  if (error || least_bytes <= size) return "";
  return "the PLY header claims " + claims + ", more than its " +
         std::to_string(static_cast<long long>(size)) + " bytes can hold";
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) int owsim_mesh_module_abi(void) {
  return OWSIM_MESH_MODULE_ABI;
}

__attribute__((visibility("default"))) int owsim_mesh_read(const char* path, owsim_mesh_sink sink,
                                                           owsim_mesh_file_sink file_sink,
                                                           void* sink_context, char* error,
                                                           std::size_t error_size) {
  try {
    if (const std::string problem = ply_counts_problem(path); !problem.empty()) {
      copy_error(problem, error, error_size);
      return 1;
    }
    Assimp::Importer importer;
    auto* files = new ConfinedIOSystem(path);  // the importer owns it
    importer.SetIOHandler(files);
    // Points and lines stay in the meshes and are skipped below: only triangles reach the sink.
    const aiScene* scene =
        importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                    aiProcess_PreTransformVertices);
    if (!files->refused().empty()) {
      copy_error("the mesh refers to " + files->refused() +
                     ", which is not a regular file beside or below it; a mesh reads only those",
                 error, error_size);
      return 1;
    }
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
    for (const std::string& file : files->opened()) file_sink(sink_context, file.c_str());
    return 0;
  } catch (const std::bad_alloc&) {
    copy_error("the mesh does not fit in memory", error, error_size);
  } catch (const std::exception& e) {
    copy_error(std::string("cannot read the mesh: ") + e.what(), error, error_size);
  } catch (...) {
    copy_error("cannot read the mesh: unknown error", error, error_size);
  }
  return 1;
}
}
