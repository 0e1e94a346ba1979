#include "io/scenario/gdal_module.hpp"

#include <string>

#include "geometry/error.hpp"
#include "io/scenario/gdal_module_abi.hpp"

namespace owsim {

const OptionalModule& gdal_module(std::string_view purpose) {
  const OptionalModule& module = OptionalModule::get("gdal", purpose);
  const auto abi =
      reinterpret_cast<owsim_gdal_module_abi_fn>(module.symbol("owsim_gdal_module_abi"));
  if (abi() != OWSIM_GDAL_MODULE_ABI) {
    throw Error(std::string(purpose) + " needs " + module.path() + " of interface " +
                std::to_string(OWSIM_GDAL_MODULE_ABI) + ", found " + std::to_string(abi()));
  }
  return module;
}

}  // namespace owsim
