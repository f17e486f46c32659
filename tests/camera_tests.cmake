# Camera, camera paths and sky (included from tests/CMakeLists.txt). Pure
# CPU code: the sources are compiled straight in, so these tests need no GPU
# and no Vulkan loader.
add_executable(test_camera
  ${CMAKE_CURRENT_LIST_DIR}/test_camera.c
  ${PROJECT_SOURCE_DIR}/core/runtime/src/camera.c
  ${PROJECT_SOURCE_DIR}/core/tools/src/camera_path.c
  ${PROJECT_SOURCE_DIR}/core/voxel/src/sky.c)
target_include_directories(test_camera PRIVATE ${PROJECT_SOURCE_DIR}/core/runtime/include
  ${PROJECT_SOURCE_DIR}/core/voxel/include ${PROJECT_SOURCE_DIR}/core/tools/include)
target_link_libraries(test_camera PRIVATE m)
# shipped_paths reads graphs/paths/*.path from the source tree
target_compile_definitions(test_camera PRIVATE VRG_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
foreach(case projection path_keys path_errors world_range sun shipped_paths)
  add_test(NAME camera_${case} COMMAND test_camera ${case})
  set_tests_properties(camera_${case} PROPERTIES LABELS "camera" TIMEOUT 120)
endforeach()
