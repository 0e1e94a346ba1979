#include "io/scenario/gdal_module.hpp"

#include "io/scenario/gdal_module_abi.hpp"

namespace owsim {

const OptionalModule& gdal_module(std::string_view purpose) {
  return OptionalModule::get("gdal", purpose, OWSIM_GDAL_MODULE_ABI);
}

}  // namespace owsim
