# One library per module: sources are every .cc in src/<module>, public headers live in
# include/fusemap/<module>. DEPS names lower modules or imported targets, so the build
# enforces the dependency direction of STYLE.md.
function(fusemap_module name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB srcs CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
  if(NOT srcs)
    # Header-only so far: still a target, so links and dependency order stay the same.
    add_library(fusemap_${name} INTERFACE)
    target_include_directories(fusemap_${name} INTERFACE ${PROJECT_SOURCE_DIR}/include)
    target_link_libraries(fusemap_${name} INTERFACE ${ARG_DEPS})
    return()
  endif()
  add_library(fusemap_${name} STATIC ${srcs})
  target_include_directories(fusemap_${name} PUBLIC ${PROJECT_SOURCE_DIR}/include)
  target_link_libraries(fusemap_${name} PUBLIC ${ARG_DEPS})
  target_compile_options(fusemap_${name} PRIVATE -Wall -Wextra)
endfunction()

# A tool binary: fusemap_tool(fusemap_offline SOURCES main.cc DEPS fusemap_io ...)
# The binary keeps its name even where a module library already has it (fusemap_eval,
# fusemap_sim): the target then gets a _tool suffix and only the output file is `name`.
function(fusemap_tool name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  set(target ${name})
  if(TARGET ${name})
    set(target ${name}_tool)
  endif()
  add_executable(${target} ${ARG_SOURCES})
  set_target_properties(${target} PROPERTIES OUTPUT_NAME ${name})
  target_link_libraries(${target} PRIVATE ${ARG_DEPS})
  target_compile_options(${target} PRIVATE -Wall -Wextra)
endfunction()
