# owsim_add_module(NAME [FOLDER DIR] PUBLIC_DEPS ... PRIVATE_DEPS ...)
# One library owsim_NAME per top-level folder, static (or shared: OWSIM_MODULE_LIBRARY_TYPE):
# DIR/*.cpp (DIR = NAME unless given), headers beside them, included as "DIR/header.hpp" from the
# repository root. Installed headers go to include/owsim/DIR/.
function(owsim_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                         -Wno-sign-conversion)
endfunction()

# Code generation for owsim's own code: no errno from the math functions (nothing reads it), so
# sqrt is one instruction and loops that take square roots vectorise. Results are unchanged: the
# functions return the same correctly rounded values either way.
function(owsim_set_codegen target)
  target_compile_options(${target} PRIVATE -fno-math-errno)
endfunction()

function(owsim_add_module name)
  cmake_parse_arguments(ARG "" "FOLDER" "PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  set(folder ${name})
  if(ARG_FOLDER)
    set(folder ${ARG_FOLDER})
  endif()
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${folder}/*.cpp)
  file(GLOB headers CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${folder}/*.hpp)
  add_library(owsim_${name} ${OWSIM_MODULE_LIBRARY_TYPE} ${sources} ${headers})
  add_library(owsim::${name} ALIAS owsim_${name})
  set_target_properties(owsim_${name} PROPERTIES EXPORT_NAME ${name} LINKER_LANGUAGE CXX)
  target_include_directories(owsim_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}>
    $<INSTALL_INTERFACE:include/owsim>)
  target_link_libraries(owsim_${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  owsim_set_warnings(owsim_${name})
  owsim_set_codegen(owsim_${name})
  if(OWSIM_LTO_FLAGS)
    target_compile_options(owsim_${name} PRIVATE ${OWSIM_LTO_FLAGS} -ffat-lto-objects)
  endif()
  install(FILES ${headers} DESTINATION include/owsim/${folder} COMPONENT dev)
endfunction()
