#pragma once
// owsim's optional modules: shared objects named libowsim_<name>.so that hold what only some
// runs need and that pull in heavy libraries (OpenImageIO for quick-look PNGs), loaded with
// dlopen the first time a run asks for them, so that a process that never writes an image never
// maps those libraries (issue 16: start-up of `owsim`, libowsim_c.so and the Python module).
//
// Where a module is looked for: only in $OWSIM_MODULE_DIR when that is set; otherwise beside the
// object that holds owsim's code (the owsim executable, libowsim_c.so, the Python module, or a
// program linking the static libraries), in `lib/owsim`, `../lib/owsim`, `owsim` and
// `../../owsim` relative to its folder (the build tree and an install prefix), then in the
// install prefix's module folder compiled in (OWSIM_INSTALLED_MODULE_DIR).
#include <string>
#include <string_view>

namespace owsim {

class OptionalModule {
 public:
  // The loaded module libowsim_<name>.so, loaded on the first call and kept for the process's
  // lifetime; thread-safe. Throws owsim::Error with one line naming the module, what needs it
  // (`purpose`), where it was looked for and the loader's reason.
  static const OptionalModule& get(std::string_view name, std::string_view purpose);
  // The same, with the module's interface version checked: its entry point
  // `int owsim_<name>_module_abi(void)` must return `abi`; otherwise owsim::Error names both.
  static const OptionalModule& get(std::string_view name, std::string_view purpose, int abi);

  // The address of `symbol` in the module; throws owsim::Error if it is missing.
  [[nodiscard]] void* symbol(const char* symbol) const;
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  OptionalModule(void* handle, std::string path) : handle_(handle), path_(std::move(path)) {}
  void* handle_;
  std::string path_;
};

}  // namespace owsim
