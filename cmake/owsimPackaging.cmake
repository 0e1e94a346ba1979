# The man pages, bash completion and documents of the owsim command, and the Debian packages CPack
# makes of an install (scripts/package.sh):
#   owsim          the command, libowsim_c.so, the optional modules, man pages, bash completion,
#                  documents (component owsim)
#   libowsim-dev   headers, static libraries, the CMake package, owsim.pc (component dev)
#   python3-owsim  the Python module (component python)
# A package's shared-library dependencies, and owsim's Recommends and Suggests, are filled in by
# scripts/package.sh (dpkg-shlibdeps):
# the command's and libowsim_c.so's as Depends, the optional modules' as Recommends (MPI's as
# Suggests), so that installing owsim never requires GDAL, assimp, OpenImageIO or MPI.

# Man pages from the command's own help text (cli/man/man_pages.sh, help2man).
find_program(OWSIM_HELP2MAN help2man)
if(OWSIM_HELP2MAN)
  set(OWSIM_HELP2MAN_FOUND TRUE)
endif()
owsim_optional(OWSIM_HELP2MAN "the man pages" package help2man)
if(OWSIM_HELP2MAN)
  set(OWSIM_MAN_DIR ${CMAKE_BINARY_DIR}/man)
  add_custom_command(OUTPUT ${OWSIM_MAN_DIR}/owsim.1.gz
    COMMAND ${CMAKE_COMMAND} -E rm -rf ${OWSIM_MAN_DIR}
    COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/cli/man/man_pages.sh $<TARGET_FILE:owsim_cli>
            ${OWSIM_MAN_DIR}
    DEPENDS owsim_cli ${CMAKE_CURRENT_SOURCE_DIR}/cli/man/man_pages.sh
            ${CMAKE_CURRENT_SOURCE_DIR}/cli/man/owsim.h2m
    COMMENT "Man pages from owsim --help (help2man)")
  add_custom_target(owsim_man_pages ALL DEPENDS ${OWSIM_MAN_DIR}/owsim.1.gz)
  install(DIRECTORY ${OWSIM_MAN_DIR}/ DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT owsim
          FILES_MATCHING PATTERN "*.1.gz")
endif()
install(FILES cli/man/owsim.bash DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions
        RENAME owsim COMPONENT owsim)
install(FILES README.md CHANGELOG.md DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT owsim)
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs COMPONENT owsim)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME owsim)
set(CPACK_PACKAGE_VENDOR owsim)
set(CPACK_PACKAGE_CONTACT "owsim developers <owsim@localhost>")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY ${PROJECT_DESCRIPTION})
set(CPACK_PACKAGING_INSTALL_PREFIX ${CMAKE_INSTALL_PREFIX})
set(CPACK_STRIP_FILES ON)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL owsim dev python)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_OWSIM_PACKAGE_NAME owsim)
set(CPACK_DEBIAN_DEV_PACKAGE_NAME libowsim-dev)
set(CPACK_DEBIAN_PYTHON_PACKAGE_NAME python3-owsim)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
set(CPACK_COMPONENT_OWSIM_DESCRIPTION
"MilOWS/HELLAS obstacle-warning LiDAR simulator
 owsim flies a helicopter obstacle-warning LiDAR along a recorded or planned
 trajectory through power-line wires, poles, trees and terrain, traces every
 laser pulse with Embree and writes the sensor's native words, point clouds,
 ground truth and detection evidence. This package holds the owsim command,
 the C library libowsim_c.so and the optional modules (quick-look images, DEM
 terrain, model files, mpirun), with man pages and bash completion.")
set(CPACK_COMPONENT_DEV_DESCRIPTION
"MilOWS/HELLAS obstacle-warning LiDAR simulator - development files
 Headers, static libraries, the CMake package (find_package(owsim), target
 owsim::owsim and owsim::owsim_c) and owsim.pc for embedding owsim in C and
 C++ programs.")
set(CPACK_COMPONENT_PYTHON_DESCRIPTION
"MilOWS/HELLAS obstacle-warning LiDAR simulator - Python module
 import owsim: simulate frames into numpy arrays, run whole flights.")
# Between owsim's own packages, the same version exactly; the dev package's static libraries link
# the -dev packages of what owsim's libraries use (cmake/owsimLibraryDependencies.cmake).
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS
    "owsim (= ${PROJECT_VERSION}), libeigen3-dev (>= 3.4), libembree-dev (>= 3.13), libtbb-dev, \
libyaml-cpp-dev, nlohmann-json3-dev, libgeographiclib-dev, zlib1g-dev, libnova-dev, \
libzstd-dev, pkg-config")
set(CPACK_DEBIAN_OWSIM_PACKAGE_CONTROL_EXTRA ${CMAKE_CURRENT_SOURCE_DIR}/cmake/deb/triggers)
include(CPack)
