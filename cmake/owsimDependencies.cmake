# Every third-party package the build uses, found in one place (Debian 12 packages; the part of
# scripts/setup.sh that installs each is named in its message).
include(owsimLibraryDependencies)   # what the libraries link (also the installed package's)
find_package(CLI11 REQUIRED)        # the owsim command
find_package(fmt REQUIRED)
find_package(PkgConfig REQUIRED)
# owsim studio's HTTP server (studio/): Debian's compiled cpp-httplib, with the flags it was built
# with (they change its classes' layout).
pkg_check_modules(HTTPLIB REQUIRED IMPORTED_TARGET GLOBAL cpp-httplib)

# An optional part is built when its packages are found; without them the rest builds and the
# part's message names the packages. OWSIM_REQUIRE_ALL (scripts/test.sh, CI) makes each required.
# owsim_optional(VAR WHAT SETUP_PART PACKAGES): VAR_FOUND is the finding; reports or fails.
function(owsim_optional var what setup_part packages)
  if(${var}_FOUND)
    return()
  endif()
  set(message "owsim: ${what} not built: needs ${packages} (scripts/setup.sh ${setup_part})")
  if(OWSIM_REQUIRE_ALL)
    message(FATAL_ERROR "${message}")
  endif()
  message(STATUS "${message}")
endfunction()

# OpenImageIO: only the optional module libowsim_png.so (quicklook/ images) links it. Debian 12's
# OpenImageIOConfig.cmake references tools from another package (openimageio-tools) and fails
# without them; its pkg-config file is complete, so use that.
pkg_check_modules(OpenImageIO IMPORTED_TARGET GLOBAL OpenImageIO)
owsim_optional(OpenImageIO "libowsim_png.so (quicklook/ images)" png libopenimageio-dev)
# GDAL: only the optional module libowsim_gdal.so (DEM terrain, GIS lines) links it.
pkg_check_modules(GDAL IMPORTED_TARGET GLOBAL gdal)
owsim_optional(GDAL "libowsim_gdal.so (DEM terrain, GIS lines)" gdal libgdal-dev)
# assimp and tinyobjloader (OBJ, double coordinates): only the optional module libowsim_mesh.so
# (triangle meshes) links them.
pkg_check_modules(ASSIMP IMPORTED_TARGET GLOBAL assimp)
pkg_check_modules(TINYOBJLOADER IMPORTED_TARGET GLOBAL tinyobjloader_double)
if(ASSIMP_FOUND AND TINYOBJLOADER_FOUND)
  set(OWSIM_MESH_FOUND TRUE)
endif()
owsim_optional(OWSIM_MESH "libowsim_mesh.so (model files)" mesh
               "libassimp-dev and libtinyobjloader-dev")
# MPI (Debian's OpenMPI): with it, libowsim_mpi.so is built and `mpirun … owsim` runs
# distributed (distributed/); without it owsim runs on one machine.
find_package(MPI COMPONENTS C)
owsim_optional(MPI_C "libowsim_mpi.so (mpirun … owsim)" mpi libopenmpi-dev)
