// libowsim_mesh.so: the one place owsim touches assimp and tinyobjloader. Loaded on demand by
// io/scenario/mesh_file.cpp when a scenario places meshes, so that the owsim executable,
// libowsim_c.so and the Python module never map assimp and the library tree behind it. The entry
// points are plain C: no exception crosses them.
//
// An OBJ is read by tinyobjloader, any other format by assimp: every mesh of the file is taken
// with its node's transformation applied (assimp's PreTransformVertices), polygons split into
// triangles; the coordinates are the file's own (no axis conversion: io/scenario/mesh_file.hpp
// says which axis is up).
#include <assimp/DefaultIOSystem.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
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

// The files a model file may make its reader open: regular files in the model's folder tree
// (symbolic links followed; issue 33). Keeps the first name refused and every other file opened,
// so a run folder can copy the model with them.
class ModelFolder {
 public:
  explicit ModelFolder(const std::filesystem::path& model) {
    std::error_code error;
    root_ =
        std::filesystem::canonical(model.parent_path().empty() ? "." : model.parent_path(), error);
    model_ = std::filesystem::canonical(model, error);  // empty when it cannot be resolved
  }

  [[nodiscard]] const std::filesystem::path& root() const { return root_; }

  // The file's real path when it may be opened, else nothing.
  [[nodiscard]] std::optional<std::filesystem::path> allowed(
      const std::filesystem::path& file) const {
    std::error_code error;
    const std::filesystem::path real = std::filesystem::canonical(file, error);
    if (error || root_.empty() || !std::filesystem::is_regular_file(real, error)) return {};
    const std::filesystem::path relative = real.lexically_relative(root_);
    if (relative.empty() || *relative.begin() == "..") return {};
    return real;
  }

  // `file` when it may be opened (recorded as opened), else nothing (recorded as refused).
  std::optional<std::filesystem::path> open(const std::filesystem::path& file) {
    std::optional<std::filesystem::path> path = allowed(file);
    if (!path) {
      refuse(file.string());
    } else if (*path != model_) {
      opened_.insert(path->string());
    }
    return path;
  }
  void refuse(const std::string& file) {
    if (refused_.empty()) refused_ = file.empty() ? "an empty name" : file;
  }

  [[nodiscard]] const std::string& refused() const { return refused_; }
  [[nodiscard]] const std::set<std::string>& opened() const { return opened_; }

 private:
  std::filesystem::path model_;
  std::filesystem::path root_;
  std::string refused_;
  std::set<std::string> opened_;
};

// assimp's file access through a ModelFolder: a name it refuses is not opened, and the read then
// fails naming it.
class ConfinedIOSystem : public Assimp::DefaultIOSystem {
 public:
  explicit ConfinedIOSystem(ModelFolder& folder) : folder_(&folder) {}

  bool Exists(const char* file) const override { return folder_->allowed(file).has_value(); }

  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (std::strpbrk(mode, "wa+") != nullptr) {  // never written
      folder_->refuse(file);
      return nullptr;
    }
    const std::optional<std::filesystem::path> path = folder_->open(file);
    return path ? DefaultIOSystem::Open(path->c_str(), mode)
                : nullptr;  // no exception through assimp
  }

 private:
  ModelFolder* folder_;
};

// tinyobjloader's material libraries through a ModelFolder, named relative to the OBJ's folder.
// owsim uses no material, but a library is read as any OBJ reader would, so that a run folder's
// copy of the model is complete and a hostile name is refused like assimp's.
class ConfinedMaterials : public tinyobj::MaterialReader {
 public:
  explicit ConfinedMaterials(ModelFolder& folder) : folder_(&folder) {}

  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* names, std::string* warning,
                  std::string* error) override {
    const std::filesystem::path given(name);
    const std::optional<std::filesystem::path> path =
        folder_->open(given.is_absolute() ? given : folder_->root() / given);
    if (!path) return false;
    std::ifstream stream(*path);
    if (!stream) return false;
    tinyobj::LoadMtl(names, materials, &stream, warning, error);
    return true;
  }

 private:
  ModelFolder* folder_;
};

// The model as vertices (3 doubles each) and triangles (3 vertex indices each).
struct Triangles {
  std::vector<double> xyz;
  std::vector<unsigned> corners;
};

// An OBJ through tinyobjloader (double coordinates, polygons triangulated): ~20 times faster than
// assimp's OBJ reader on a 3 M-triangle model (README "Meshes").
bool read_obj(const std::filesystem::path& path, ModelFolder& folder, Triangles& out,
              std::string& problem) {
  std::ifstream stream(path);
  if (!stream) {
    problem = "cannot open the mesh";
    return false;
  }
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warning, error;
  ConfinedMaterials library(folder);
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &stream, &library, true)) {
    problem = "cannot read the mesh: " + first_line(error.c_str());
    return false;
  }
  out.xyz.assign(attrib.vertices.begin(), attrib.vertices.end());
  const std::size_t vertices = out.xyz.size() / 3;
  for (const tinyobj::shape_t& shape : shapes) {
    const std::vector<tinyobj::index_t>& indices = shape.mesh.indices;
    std::size_t at = 0;
    for (const unsigned char corners : shape.mesh.num_face_vertices) {
      if (corners == 3) {
        for (std::size_t c = 0; c < 3; ++c) {
          const int index = indices[at + c].vertex_index;
          if (index < 0 || static_cast<std::size_t>(index) >= vertices) {
            problem = "cannot read the mesh: a face names vertex " + std::to_string(index + 1) +
                      " of " + std::to_string(vertices);
            return false;
          }
          out.corners.push_back(static_cast<unsigned>(index));
        }
      }
      at += corners;
    }
  }
  return true;
}

// Any other format through assimp: every mesh of the file with its node's transformation
// applied, polygons split into triangles (fans: convex polygons, as PLY and glTF hold), points and
// lines left out.
bool read_with_assimp(const std::filesystem::path& path, ModelFolder& folder, Triangles& out,
                      std::string& problem) {
  Assimp::Importer importer;
  importer.SetIOHandler(new ConfinedIOSystem(folder));  // the importer owns it
  const aiScene* scene = importer.ReadFile(
      path.c_str(), aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices);
  if (scene == nullptr) {
    problem = "cannot read the mesh: " + first_line(importer.GetErrorString());
    return false;
  }
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const auto first = static_cast<unsigned>(out.xyz.size() / 3);
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& vertex = mesh->mVertices[v];
      out.xyz.insert(out.xyz.end(), {static_cast<double>(vertex.x), static_cast<double>(vertex.y),
                                     static_cast<double>(vertex.z)});
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      // Polygons as fans from their first corner (not assimp's Triangulate step, which aborts the
      // process on some malformed faces: found by fuzz_scene_files); points and lines left out.
      const aiFace& face = mesh->mFaces[f];
      for (unsigned c = 2; c < face.mNumIndices; ++c) {
        for (const unsigned corner : {face.mIndices[0], face.mIndices[c - 1], face.mIndices[c]}) {
          if (corner >= mesh->mNumVertices) {
            problem = "cannot read the mesh: a face names a vertex it does not have";
            return false;
          }
          out.corners.push_back(first + corner);
        }
      }
    }
  }
  return true;
}

// The file name's extension in lower case (".obj").
std::string extension_of(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// `text` with every byte outside printable ASCII as '?': a file's bytes quoted in a message.
std::string printable(std::string text) {
  for (char& c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
  }
  return text;
}

// The bytes a PLY scalar type takes in a binary file, or 0 for a name that is not a PLY type.
int ply_type_bytes(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" ||
      type == "float32") {
    return 4;
  }
  if (type == "double" || type == "float64") return 8;
  return 0;
}

// A PLY header checked before assimp reads it: its lines must be the format's (assimp 5.2 loops
// forever on a header whose format line holds other bytes, and leaks on a property of an unknown
// type; both found by fuzz_scene_files), and its
// element counts must fit the file's size (a header claiming 4·10⁹ faces in a 200-byte file ran
// out of memory): every element takes at least 2 bytes in ASCII (a digit and a line end) and its
// fixed-size properties' bytes in binary (a list at least its count's size). Returns the problem,
// or "" when the header is sound.
std::string ply_header_problem(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::string line;
  const bool has_line = static_cast<bool>(std::getline(file, line));
  if (!line.empty() && line.back() == '\r') line.pop_back();
  std::string magic = line.substr(0, 3);
  std::transform(magic.begin(), magic.end(), magic.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  // assimp takes a .ply file, or one starting "ply" in any case, as a PLY: it must be one.
  if (extension_of(path) != ".ply" && magic != "ply") return "";
  if (!has_line || line != "ply") return "its first line is not 'ply', as a PLY file's is";
  bool ascii = true;
  double least_bytes = 0.0;
  double count = 0.0;
  double element_bytes = 0.0;
  std::string claims;
  const auto close_element = [&] {
    least_bytes += count * (ascii ? 2.0 : std::max(1.0, element_bytes));
  };
  bool ended = false;
  for (int lines = 0; lines < 10'000 && std::getline(file, line); ++lines) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (printable(line) != line) {
      return "line " + std::to_string(lines + 2) +
             " of its PLY header holds bytes that are not text";
    }
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "format") {
      std::string format, version, rest;
      words >> format >> version >> rest;
      if ((format != "ascii" && format != "binary_little_endian" &&
           format != "binary_big_endian") ||
          version != "1.0" || !rest.empty()) {
        return "its PLY format line is not 'format ascii|binary_little_endian|binary_big_endian "
               "1.0'";
      }
      ascii = format == "ascii";
    } else if (keyword == "comment" || keyword == "obj_info") {
      continue;
    } else if (keyword == "element") {
      close_element();
      std::string name, count_text;
      words >> name >> count_text;
      if (name.empty() || count_text.empty() ||
          count_text.find_first_not_of("0123456789") != std::string::npos) {
        return "line " + std::to_string(lines + 2) +
               " of its PLY header is not 'element NAME COUNT'";
      }
      // As written, not converted: a count like 1e55 does not fit an integer.
      count = std::strtod(count_text.c_str(), nullptr);
      if (!(count >= 0.0)) count = 0.0;  // NaN or negative: assimp refuses the file itself
      element_bytes = 0.0;
      claims += (claims.empty() ? "" : ", ") + printable(count_text.substr(0, 24)) + " " +
                printable(name.substr(0, 24));
    } else if (keyword == "property") {
      std::string type, count_type, name;
      words >> type;
      if (type == "list") words >> count_type >> type;
      words >> name;
      if (ply_type_bytes(type) == 0 || (!count_type.empty() && ply_type_bytes(count_type) == 0) ||
          name.empty()) {
        return "line " + std::to_string(lines + 2) +
               " of its PLY header is not a property of a PLY type";
      }
      element_bytes += ply_type_bytes(count_type.empty() ? type : count_type);
    } else if (keyword == "end_header") {
      ended = true;
      break;
    } else {
      return "line " + std::to_string(lines + 2) + " of its PLY header is not a header line";
    }
  }
  if (!ended) return "its PLY header has no end_header line";
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
    if (const std::string problem = ply_header_problem(path); !problem.empty()) {
      copy_error(problem, error, error_size);
      return 1;
    }
    ModelFolder folder(path);
    Triangles mesh;
    std::string problem;
    const bool read = extension_of(path) == ".obj" ? read_obj(path, folder, mesh, problem)
                                                   : read_with_assimp(path, folder, mesh, problem);
    if (!folder.refused().empty()) {
      copy_error("the mesh refers to " + folder.refused() +
                     ", which is not a regular file beside or below it; a mesh reads only those",
                 error, error_size);
      return 1;
    }
    if (!read) {
      copy_error(problem, error, error_size);
      return 1;
    }
    sink(sink_context, mesh.xyz.size() / 3, mesh.xyz.data(), mesh.corners.size() / 3,
         mesh.corners.data());
    for (const std::string& file : folder.opened()) file_sink(sink_context, file.c_str());
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
