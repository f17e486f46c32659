# voxrg_add_pass(NAME SOURCES file.c... [SHADERS file.comp...]
#                [LIBRARIES target...] [DESTINATION folder])
# Builds the plugin NAME.so (a MODULE, no "lib" prefix: the runtime finds a
# plugin by its file name) against the installed voxrg headers. In the build
# folder its shaders are read where they are written (VRG_PLUGIN_DIR is the
# folder of the first shader, so saving one hot-reloads it); `cmake --install`
# copies NAME.so to DESTINATION (default lib/voxrg/plugins under the install
# prefix) and its shaders to DESTINATION/NAME/, where the runtime looks for
# an installed plugin's shaders (and only there: where that folder exists,
# VRG_PLUGIN_DIR is not searched). A scene plugin of the voxel world adds
# LIBRARIES voxrg::voxel. Built and installed, NAME.so has a RUNPATH to this
# SDK's lib folder, so it finds libvoxrg_voxel (and the rest) wherever the
# host program comes from.
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
  target_compile_definitions(${name} PRIVATE VRG_PLUGIN_DIR="${shader_dir}")
  target_link_libraries(${name} PRIVATE voxrg::voxrg ${VRG_PASS_LIBRARIES})
  set_target_properties(${name} PROPERTIES PREFIX "" C_VISIBILITY_PRESET hidden
                        BUILD_RPATH "${_voxrg_lib_dir}" INSTALL_RPATH "${_voxrg_lib_dir}")
  install(TARGETS ${name} LIBRARY DESTINATION ${VRG_PASS_DESTINATION})
  if(shaders)
    install(FILES ${shaders} DESTINATION ${VRG_PASS_DESTINATION}/${name})
  endif()
endfunction()
