# Warnings for sslr's own targets.
function(sslr_set_warnings target)
  if(MSVC)
    target_compile_options(${target} PRIVATE /W4)
  else()
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow)
  endif()
  if(SSLR_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE $<IF:$<CXX_COMPILER_ID:MSVC>,/WX,-Werror>)
  endif()
endfunction()

# sslr_embed_shaders(<out-var> NAMESPACE ns ROOT dir OUTPUT file.cpp ENTRIES a.comp ...)
# Generates OUTPUT at build time; it is regenerated whenever any file under ROOT changes.
function(sslr_embed_shaders out_var)
  cmake_parse_arguments(ARG "" "NAMESPACE;ROOT;OUTPUT" "ENTRIES" ${ARGN})
  file(GLOB_RECURSE shader_files CONFIGURE_DEPENDS ${ARG_ROOT}/*.h ${ARG_ROOT}/*.glsl
       ${ARG_ROOT}/*.comp ${ARG_ROOT}/*.vert ${ARG_ROOT}/*.frag)
  add_custom_command(OUTPUT ${ARG_OUTPUT}
    COMMAND sslr_embed_shaders ${ARG_OUTPUT} ${ARG_NAMESPACE} ${ARG_ROOT} ${ARG_ENTRIES}
    DEPENDS sslr_embed_shaders ${shader_files}
    COMMENT "Embedding shaders from ${ARG_ROOT}"
    VERBATIM)
  set(${out_var} ${ARG_OUTPUT} PARENT_SCOPE)
endfunction()
