# Installs owsim::owsim with a CMake package config so that an outside project can
#   find_package(owsim REQUIRED)  target_link_libraries(app PRIVATE owsim::owsim)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS owsim owsim_geometry owsim_sensor owsim_detection owsim_engine owsim_io owsim_io_files
                owsim_io_scenario owsim_io_trajectory owsim_io_points owsim_io_images
                owsim_io_recording owsim_io_run owsim_io_sweep owsim_io_report owsim_io_mcap
                owsim_io_detections
                owsim_evaluation owsim_facade
        EXPORT owsimTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev  # OWSIM_MODULE_LIBRARY_TYPE=SHARED
        INCLUDES DESTINATION include/owsim)
install(TARGETS owsim_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT owsim)
foreach(module png gdal mesh mpi)   # the optional modules this build has
  if(TARGET owsim_${module})
    install(TARGETS owsim_${module} LIBRARY DESTINATION ${OWSIM_MODULE_INSTALL_DIR}
            COMPONENT owsim)
  endif()
endforeach()
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/generated/owsim/version.hpp DESTINATION include/owsim/owsim
        COMPONENT dev)
install(EXPORT owsimTargets NAMESPACE owsim:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/owsim
        COMPONENT dev)

configure_package_config_file(cmake/owsimConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/owsimConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/owsim)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/owsimConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/owsimConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/owsimConfigVersion.cmake
              ${CMAKE_CURRENT_SOURCE_DIR}/cmake/owsimLibraryDependencies.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/owsim COMPONENT dev)
