# The third-party packages owsim's libraries (owsim::owsim, owsim::owsim_c) link: found by the
# build and, installed beside owsimConfig.cmake, by a program that does find_package(owsim).
# Their Debian -dev packages are what libowsim-dev depends on (cmake/owsimPackaging.cmake).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(embree 3.13 REQUIRED)
find_package(TBB REQUIRED)
find_package(yaml-cpp REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(ZLIB REQUIRED)   # deflate of the report page's data (io/report/), MCAP's CRC-32
# zstd: the chunks of flight.mcap (io/mcap/), through its pkg-config file (hence pkg-config in
# libowsim-dev's Depends).
find_package(PkgConfig REQUIRED)
pkg_check_modules(ZSTD REQUIRED IMPORTED_TARGET libzstd)

# GeographicLib ships only a find module on Debian; wrap its variables in a target.
list(APPEND CMAKE_MODULE_PATH /usr/share/cmake/geographiclib)
find_package(GeographicLib REQUIRED)
if(NOT TARGET owsim::GeographicLib)
  add_library(owsim::GeographicLib INTERFACE IMPORTED)
  set_target_properties(owsim::GeographicLib PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${GeographicLib_INCLUDE_DIRS}"
    INTERFACE_LINK_LIBRARIES "${GeographicLib_LIBRARIES}")
endif()

# libnova (Debian's libnova-dev ships no pkg-config or CMake file): the sun's position for a
# scenario's `sun: {time_utc}` (io/scenario/solar_position.hpp), linked by io/scenario only.
find_library(OWSIM_LIBNOVA_LIBRARY NAMES nova)
find_path(OWSIM_LIBNOVA_INCLUDE_DIR libnova/solar.h)
if(NOT OWSIM_LIBNOVA_LIBRARY OR NOT OWSIM_LIBNOVA_INCLUDE_DIR)
  message(FATAL_ERROR "owsim: needs libnova (libnova-dev; scripts/setup.sh core)")
endif()
if(NOT TARGET owsim::libnova)
  add_library(owsim::libnova INTERFACE IMPORTED)
  set_target_properties(owsim::libnova PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${OWSIM_LIBNOVA_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${OWSIM_LIBNOVA_LIBRARY}")
endif()
