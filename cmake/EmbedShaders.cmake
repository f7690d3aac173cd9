# Compiles GLSL compute shaders to SPIR-V with glslangValidator at build time and
# embeds the words in a C++ header, so the binaries run from any directory.
# glslang's depfile makes an edit to any #included GLSL file trigger a rebuild.

# vkdr_embed_shaders(TARGET <name> SOURCES <file.comp>... INCLUDE_DIRS <dir>...)
# Creates a static library <name> exposing "<name>.h" with one
#   std::span<const uint32_t> <stem>Spirv()
# accessor per shader (stem: the file name without extension, camelCased).
function(vkdr_embed_shaders)
  cmake_parse_arguments(ARG "" "TARGET" "SOURCES;INCLUDE_DIRS" ${ARGN})
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/${ARG_TARGET})
  file(MAKE_DIRECTORY ${out_dir})
  set(include_flags)
  foreach(dir ${ARG_INCLUDE_DIRS})
    list(APPEND include_flags -I${dir})
  endforeach()
  set(headers)
  set(declarations "")
  set(definitions "")
  foreach(src ${ARG_SOURCES})
    get_filename_component(stem ${src} NAME_WE)
    string(REGEX REPLACE "_([a-z])" "\\1" camel ${stem})
    string(REGEX MATCHALL "_[a-z]" letters ${stem})
    set(camel ${stem})
    foreach(pair ${letters})
      string(SUBSTRING ${pair} 1 1 letter)
      string(TOUPPER ${letter} upper)
      string(REPLACE ${pair} ${upper} camel ${camel})
    endforeach()
    get_filename_component(abs_src ${src} ABSOLUTE)
    set(header ${out_dir}/${stem}.spv.h)
    add_custom_command(
      OUTPUT ${header}
      COMMAND ${GLSLANG_VALIDATOR} --quiet --target-env vulkan1.2 -g0 ${include_flags}
              --vn k_${stem}_spirv --depfile ${header}.d -o ${header} ${abs_src}
      DEPENDS ${abs_src}
      DEPFILE ${header}.d
      COMMENT "glslang ${stem}.comp"
      VERBATIM)
    list(APPEND headers ${header})
    string(APPEND declarations "std::span<const uint32_t> ${camel}Spirv();\n")
    string(APPEND definitions "#include \"${stem}.spv.h\"\nstd::span<const uint32_t> ${camel}Spirv() { return k_${stem}_spirv; }\n")
  endforeach()
  file(CONFIGURE OUTPUT ${out_dir}/${ARG_TARGET}.h CONTENT
"#pragma once\n#include <cstdint>\n#include <span>\nnamespace vkdr::spirv {\n${declarations}}\n")
  file(CONFIGURE OUTPUT ${out_dir}/${ARG_TARGET}.cpp CONTENT
"#include \"${ARG_TARGET}.h\"\nnamespace vkdr::spirv {\n${definitions}}\n")
  add_library(${ARG_TARGET} STATIC ${out_dir}/${ARG_TARGET}.cpp ${headers})
  target_include_directories(${ARG_TARGET} PUBLIC ${out_dir})
endfunction()
