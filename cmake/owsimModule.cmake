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

# Precompiled headers (OWSIM_PRECOMPILED_HEADERS): the standard library, Eigen and nlohmann-json
# headers most sources parse are parsed once per set of compile options, not once per source —
# a third to a half of a typical source's compile time was parsing them. Every module reuses the
# one header set compiled with the modules' own options (owsim_module_headers); targets with other
# options (the command, the studio, the tests) compile their own once.
set(OWSIM_COMMON_HEADERS <algorithm> <array> <cmath> <cstddef> <cstdint> <cstdio> <cstring>
    <filesystem> <functional> <limits> <map> <memory> <optional> <span> <string> <string_view>
    <utility> <vector> <Eigen/Core> <Eigen/Geometry> <nlohmann/json.hpp>)
function(owsim_precompile_headers target)
  if(OWSIM_PRECOMPILED_HEADERS)
    target_precompile_headers(${target} PRIVATE ${OWSIM_COMMON_HEADERS} ${ARGN})
  endif()
endfunction()

function(owsim_set_module_options target)
  owsim_set_warnings(${target})
  owsim_set_codegen(${target})
  string(REGEX REPLACE "^owsim_" "" module ${target})
  if(OWSIM_LTO_FLAGS AND (module IN_LIST OWSIM_LTO_MODULES OR module STREQUAL "module_headers"))
    target_compile_options(${target} PRIVATE ${OWSIM_LTO_FLAGS} -ffat-lto-objects)
  endif()
endfunction()

if(OWSIM_PRECOMPILED_HEADERS)
  add_library(owsim_module_headers OBJECT ${CMAKE_CURRENT_LIST_DIR}/precompiled_headers.cpp)
  target_link_libraries(owsim_module_headers PRIVATE Eigen3::Eigen nlohmann_json::nlohmann_json)
  owsim_set_module_options(owsim_module_headers)
  owsim_precompile_headers(owsim_module_headers)
endif()

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
  owsim_set_module_options(owsim_${name})
  if(OWSIM_PRECOMPILED_HEADERS)
    target_precompile_headers(owsim_${name} REUSE_FROM owsim_module_headers)
  endif()
  install(FILES ${headers} DESTINATION include/owsim/${folder} COMPONENT dev)
endfunction()
