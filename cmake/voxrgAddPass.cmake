# voxrg_add_pass(NAME SOURCES file.c... [SHADERS file.comp...]
#                [LIBRARIES target...] [DESTINATION folder])
# Builds the plugin NAME.so (a MODULE, no "lib" prefix: the runtime finds a
# plugin by its file name) against the installed voxrg headers. The runtime
# reads a plugin's shaders from the folder NAME/ beside NAME.so, so no path
# is compiled into the plugin: in the build folder NAME/ is a link to the
# folder of the shaders (saving one there hot-reloads it); `cmake --install`
# copies NAME.so to DESTINATION (default lib/voxrg/plugins under the install
# prefix) and its shaders to DESTINATION/NAME/. A scene plugin of the voxel
# world adds LIBRARIES voxrg::voxel. Built and installed, NAME.so has a
# RUNPATH to this SDK's lib folder, so it finds libvoxrg_voxel (and the
# rest) wherever the host program comes from.
get_filename_component(_voxrg_lib_dir "${CMAKE_CURRENT_LIST_DIR}/../.." ABSOLUTE)
function(voxrg_add_pass name)
  cmake_parse_arguments(VRG_PASS "" "DESTINATION" "SOURCES;SHADERS;LIBRARIES" ${ARGN})
  if(NOT VRG_PASS_SOURCES)
    message(FATAL_ERROR "voxrg_add_pass(${name}): no SOURCES given")
  endif()
  if(VRG_PASS_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "voxrg_add_pass(${name}): unknown arguments: ${VRG_PASS_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT VRG_PASS_DESTINATION)
    set(VRG_PASS_DESTINATION lib/voxrg/plugins)
  endif()
  set(shader_dir ${CMAKE_CURRENT_SOURCE_DIR})
  set(shaders "")
  foreach(shader ${VRG_PASS_SHADERS})
    get_filename_component(shader ${shader} ABSOLUTE BASE_DIR ${CMAKE_CURRENT_SOURCE_DIR})
    if(NOT EXISTS ${shader})
      message(FATAL_ERROR "voxrg_add_pass(${name}): shader ${shader} does not exist")
    endif()
    list(APPEND shaders ${shader})
  endforeach()
  if(shaders)
    list(GET shaders 0 first)
    get_filename_component(shader_dir ${first} DIRECTORY)
  endif()
  add_library(${name} MODULE ${VRG_PASS_SOURCES} ${shaders})
  if(shaders)
    if(shader_dir STREQUAL CMAKE_CURRENT_BINARY_DIR)
      message(FATAL_ERROR "voxrg_add_pass(${name}): build outside the shaders' folder ${shader_dir} "
                          "(cmake -B build): the build gets ${name}/, a link to that folder, beside ${name}.so")
    endif()
    # beside NAME.so wherever its output folder is set, after the target's
    # properties are final
    add_custom_command(TARGET ${name} POST_BUILD
      COMMAND ${CMAKE_COMMAND} -E create_symlink ${shader_dir} $<TARGET_FILE_DIR:${name}>/${name}
      VERBATIM)
  endif()
  target_link_libraries(${name} PRIVATE voxrg::voxrg ${VRG_PASS_LIBRARIES})
  if(VOXRG_PASS_IN_TREE)
    # voxrg's own build (its passes/): beside the build's plugins; installed
    # in PREFIX/lib/voxrg/plugins, the libraries are two folders up
    set_target_properties(${name} PROPERTIES PREFIX "" C_VISIBILITY_PRESET hidden
                          LIBRARY_OUTPUT_DIRECTORY ${VOXRG_PLUGIN_OUTPUT_DIR} INSTALL_RPATH "$ORIGIN/../..")
  else()
    set_target_properties(${name} PROPERTIES PREFIX "" C_VISIBILITY_PRESET hidden
                          BUILD_RPATH "${_voxrg_lib_dir}" INSTALL_RPATH "${_voxrg_lib_dir}")
  endif()
  install(TARGETS ${name} LIBRARY DESTINATION ${VRG_PASS_DESTINATION})
  if(shaders)
    install(FILES ${shaders} DESTINATION ${VRG_PASS_DESTINATION}/${name})
  endif()
endfunction()
