# Every third-party package owsim uses, found in one place (Debian 12 packages; see scripts/setup.sh).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(embree 3.13 REQUIRED)
find_package(TBB REQUIRED)
find_package(yaml-cpp REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(fmt REQUIRED)
find_package(ZLIB REQUIRED)   # deflate of the report page's data (io/report/)


# GeographicLib ships only a find module on Debian; wrap its variables in a target.
list(APPEND CMAKE_MODULE_PATH /usr/share/cmake/geographiclib)
find_package(GeographicLib REQUIRED)
if(NOT TARGET owsim::GeographicLib)
  add_library(owsim::GeographicLib INTERFACE IMPORTED)
  set_target_properties(owsim::GeographicLib PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${GeographicLib_INCLUDE_DIRS}"
    INTERFACE_LINK_LIBRARIES "${GeographicLib_LIBRARIES}")
endif()

# Debian 12's OpenImageIOConfig.cmake references tools from another package (openimageio-tools)
# and fails without them; its pkg-config file is complete, so use that.
find_package(PkgConfig REQUIRED)
pkg_check_modules(OpenImageIO REQUIRED IMPORTED_TARGET GLOBAL OpenImageIO)
# GDAL: only the optional module libowsim_gdal.so (DEM terrain) links it.
pkg_check_modules(GDAL REQUIRED IMPORTED_TARGET GLOBAL gdal)
# assimp and tinyobjloader (OBJ, double coordinates): only the optional module libowsim_mesh.so
# (triangle meshes) links them.
pkg_check_modules(ASSIMP REQUIRED IMPORTED_TARGET GLOBAL assimp)
pkg_check_modules(TINYOBJLOADER REQUIRED IMPORTED_TARGET GLOBAL tinyobjloader_double)
# owsim studio's HTTP server (studio/): Debian's compiled cpp-httplib, with the flags it was built
# with (they change its classes' layout).
pkg_check_modules(HTTPLIB REQUIRED IMPORTED_TARGET GLOBAL cpp-httplib)

# MPI (Debian's OpenMPI) is optional: with it, libowsim_mpi.so is built and `mpirun … owsim` runs
# distributed (distributed/); without it everything else builds and owsim runs on one machine.
find_package(MPI COMPONENTS C)
