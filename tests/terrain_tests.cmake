# CPU-side terrain generation and chunk streaming (included from
# tests/CMakeLists.txt). Pure C + pthreads: no GPU or Vulkan loader needed.

add_executable(test_terrain test_terrain.c
  ${PROJECT_SOURCE_DIR}/plugins/terrain/terrain_gen.c
  ${PROJECT_SOURCE_DIR}/plugins/terrain/stream.c)
target_include_directories(test_terrain PRIVATE
  ${PROJECT_SOURCE_DIR}/core/runtime/include ${PROJECT_SOURCE_DIR}/core/voxel/include ${PROJECT_SOURCE_DIR}/plugins/terrain)
# world.h pulls in plugin.h, which includes <vulkan/vulkan.h> (headers only).
if(TARGET Vulkan::Headers)
  target_link_libraries(test_terrain PRIVATE Vulkan::Headers)
endif()
target_link_libraries(test_terrain PRIVATE Threads::Threads m)
foreach(case noise determinism trees_across_borders biomes_bruteforce streaming layers perf)
  add_test(NAME terrain_${case} COMMAND test_terrain ${case})
  set_tests_properties(terrain_${case} PROPERTIES LABELS "terrain" TIMEOUT 300)
endforeach()
