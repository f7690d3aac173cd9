# The Blender add-on as Blender installs it (a zip of its folder), and the Debian package
# of everything `cmake --install` installs: `cpack -G DEB` in the build directory.

set(vkdr_addon_dir ${PROJECT_SOURCE_DIR}/tools/blender/vkdiffrender_blender)
if(IS_DIRECTORY ${vkdr_addon_dir})
  # Only the add-on's Python files, by path inside the zip (vkdiffrender_blender/...):
  # never the __pycache__ that running it from the source tree leaves.
  file(GLOB_RECURSE vkdr_addon_files CONFIGURE_DEPENDS RELATIVE ${PROJECT_SOURCE_DIR}/tools/blender
       ${vkdr_addon_dir}/*.py)
  set(vkdr_addon_zip ${CMAKE_BINARY_DIR}/blender/vkdiffrender_blender.zip)
  list(TRANSFORM vkdr_addon_files PREPEND ${PROJECT_SOURCE_DIR}/tools/blender/ OUTPUT_VARIABLE vkdr_addon_sources)
  add_custom_command(
    OUTPUT ${vkdr_addon_zip}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${CMAKE_BINARY_DIR}/blender
    COMMAND ${CMAKE_COMMAND} -E tar cf ${vkdr_addon_zip} --format=zip -- ${vkdr_addon_files}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}/tools/blender
    DEPENDS ${vkdr_addon_sources}
    COMMENT "Zipping the Blender add-on"
    VERBATIM)
  add_custom_target(vkdr_blender_addon_zip ALL DEPENDS ${vkdr_addon_zip})
  install(FILES ${vkdr_addon_zip} DESTINATION ${CMAKE_INSTALL_DATADIR}/vkdiffrender/blender)
else()
  message(STATUS "No ${vkdr_addon_dir}: the Blender add-on zip is not built or installed")
endif()

set(CPACK_PACKAGE_NAME vkdiffrender)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "differentiable Monte Carlo path tracer for participating media (Vulkan)")
string(CONCAT CPACK_PACKAGE_DESCRIPTION
    "vkdiffrender renders glTF 2.0 scenes with fog, smoke and media inside objects by\n"
    "wavefront path tracing in Vulkan compute shaders, on any GPU or on the CPU through\n"
    "Mesa's lavapipe, and differentiates the render with respect to media, surface\n"
    "colours and light strengths to fit them to target images. It ships the\n"
    "vkdiffrender command, its Python module (with a PyTorch operation), example\n"
    "scenes and a Blender add-on.")
set(CPACK_PACKAGE_CONTACT "vkdiffrender developers <vkdiffrender-devel@example.org>"
    CACHE STRING "The package's Maintainer field")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER ${CPACK_PACKAGE_CONTACT})
# The .deb installs under /usr whatever prefix the build was configured for: the binary
# finds its docs and scenes relative to itself (src/cli/install_layout.h).
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
# Line tables and symbols (tools/build.sh builds with -g1) are not needed to run it.
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
# The libraries the binary and the module link (OpenEXR, TBB, tinygltf, libstdc++, ...)
# come from dpkg-shlibdeps; what they load or import at run time is listed: the Vulkan
# loader (volk opens libvulkan.so.1 itself, so shlibdeps cannot see it), a Vulkan driver
# (lavapipe is in mesa-vulkan-drivers), and the Python and numpy the module is built for.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "libvulkan1, mesa-vulkan-drivers | vulkan-icd, python3-numpy")
# The module is built for one Python minor version: the one found at configure time.
if(VKDR_PYTHON)
  math(EXPR vkdr_next_python_minor "${Python_VERSION_MINOR} + 1")
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS
         ", python3 (>= ${Python_VERSION_MAJOR}.${Python_VERSION_MINOR}),"
         " python3 (<< ${Python_VERSION_MAJOR}.${vkdr_next_python_minor})")
endif()
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "python3-torch, blender")
include(CPack)
