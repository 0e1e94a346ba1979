#include "io/files/optional_module.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "geometry/error.hpp"

#ifndef OWSIM_INSTALLED_MODULE_DIR
#define OWSIM_INSTALLED_MODULE_DIR ""
#endif

namespace owsim {
namespace {

// The folder of the object (executable or shared library) that holds this code.
std::filesystem::path own_object_folder() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&own_object_folder), &info) == 0 ||
      info.dli_fname == nullptr) {
    return {};
  }
  std::error_code error;
  const auto path = std::filesystem::canonical(info.dli_fname, error);
  return error ? std::filesystem::path(info.dli_fname).parent_path() : path.parent_path();
}

std::vector<std::filesystem::path> module_folders() {
  if (const char* dir = std::getenv("OWSIM_MODULE_DIR"); dir != nullptr && *dir != '\0') {
    return {dir};
  }
  std::vector<std::filesystem::path> folders;
  if (const auto own = own_object_folder(); !own.empty()) {
    for (const char* relative : {"lib/owsim", "../lib/owsim", "owsim", "../../owsim"}) {
      folders.push_back((own / relative).lexically_normal());
    }
  }
  if (std::string_view(OWSIM_INSTALLED_MODULE_DIR).size() > 0) {
    folders.emplace_back(OWSIM_INSTALLED_MODULE_DIR);
  }
  return folders;
}

// What brings each module: the Debian packages it is built from (and the part of scripts/setup.sh
// that installs them), and the runtime libraries the installed owsim package's module needs.
struct ModuleSource {
  std::string_view name, build_packages, setup_part, runtime_packages;
};
constexpr ModuleSource kModuleSources[] = {
    {"png", "libopenimageio-dev", "png", "libopenimageio2.4"},
    {"gdal", "libgdal-dev", "gdal", "libgdal32"},
    {"mesh", "libassimp-dev libtinyobjloader-dev", "mesh", "libassimp5 libtinyobjloader2rc10"},
    {"mpi", "libopenmpi-dev", "mpi", "libopenmpi3"},
};

std::string where_it_comes_from(std::string_view name) {
  for (const ModuleSource& source : kModuleSources) {
    if (source.name != name) continue;
    return "; built when " + std::string(source.build_packages) +
           " is installed (scripts/setup.sh " + std::string(source.setup_part) +
           ", then build again); the owsim package's module needs " +
           std::string(source.runtime_packages) + " (apt install " +
           std::string(source.runtime_packages) + ")";
  }
  return "";
}

}  // namespace

const OptionalModule& OptionalModule::get(std::string_view name, std::string_view purpose) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<OptionalModule>, std::less<>> loaded;
  const std::lock_guard lock(mutex);
  if (const auto it = loaded.find(name); it != loaded.end()) return *it->second;

  const std::string file = "libowsim_" + std::string(name) + ".so";
  std::string searched;
  std::string reason = "not found";
  for (const auto& folder : module_folders()) {
    if (!searched.empty()) searched += ", ";
    searched += folder.string();
    const auto candidate = folder / file;
    std::error_code error;
    if (!std::filesystem::exists(candidate, error)) continue;
    void* handle = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* message = dlerror();
      reason = message != nullptr ? message : "dlopen failed";
      continue;
    }
    auto module = std::unique_ptr<OptionalModule>(new OptionalModule(handle, candidate.string()));
    return *loaded.emplace(std::string(name), std::move(module)).first->second;
  }
  throw Error(std::string(purpose) + " need the optional module " + file + ", which cannot be " +
              "loaded (" + reason + "; looked in " + (searched.empty() ? "nowhere" : searched) +
              "; OWSIM_MODULE_DIR names its folder" + where_it_comes_from(name) + ")");
}

const OptionalModule& OptionalModule::get(std::string_view name, std::string_view purpose,
                                          int abi) {
  const OptionalModule& module = get(name, purpose);
  const std::string entry = "owsim_" + std::string(name) + "_module_abi";
  using AbiFunction = int (*)();
  const int found = reinterpret_cast<AbiFunction>(module.symbol(entry.c_str()))();
  if (found != abi) {
    throw Error(std::string(purpose) + " need " + module.path() + " of interface " +
                std::to_string(abi) + ", found " + std::to_string(found));
  }
  return module;
}

void* OptionalModule::symbol(const char* symbol) const {
  dlerror();
  void* address = dlsym(handle_, symbol);
  if (address == nullptr) {
    throw Error("optional module " + path_ + " has no entry point " + symbol +
                " (a module from another owsim version?)");
  }
  return address;
}

}  // namespace owsim
