# Tests that drive the runtime (included from tests/CMakeLists.txt).
# Every test runs with the Khronos validation layer and synchronization
# validation; a validation message fails it. ASan's quarantine is kept small:
# lavapipe's JIT makes millions of tiny aligned allocations (a coroutine frame
# per few shader invocations), and ASan's chunks for them are far larger than
# the bytes its quarantine counts: svgf_mse peaked at 24 GiB resident with the
# default 256 MiB quarantine, 8.3 GiB with 64, about 2 GiB with 8.

set(VRG_TEST_ENV
  "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_SOURCE_DIR}/lsan.supp:print_suppressions=0"
  "ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:quarantine_size_mb=8"
  "UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1")

add_executable(test_runtime test_runtime.c)
target_link_libraries(test_runtime PRIVATE voxrg m)
vrg_use_fast_malloc(test_runtime)
target_compile_definitions(test_runtime PRIVATE TEST_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
set(VRG_LOADER_DIR ${CMAKE_CURRENT_BINARY_DIR}/loader_plugins)
file(MAKE_DIRECTORY ${VRG_LOADER_DIR})
foreach(case chain history history_cleared accumulate accumulate_count pingpong pingpong_alias alias buffer buffer_texels scene loader validation_live blocks_world blocks_trace terrain_world terrain_trace atlas traversal_errors camera_range rayquery gbuffer_normals gbuffer_motion backends_agree light_floor light_wall light_half_res svgf_disocclusion svgf_mse svgf_history_reset svgf_variance svgf_edge accumulate_mean svgf_atrous_options svgf_size_mismatch dispatch_shape hot_reload_shader hot_reload_graph hot_reload_plugin capture_replay soak set_param light_penumbra light_corner light_chain history_many many_uses alias_many hot_reload_many_plugins hot_reload_many_files dispatch_limits hot_reload_state_too_big)
  add_test(NAME runtime_${case} COMMAND test_runtime ${case})
  # 77: skipped (e.g. no VK_KHR_ray_query on this device), reported as such
  set_tests_properties(runtime_${case} PROPERTIES ENVIRONMENT "${VRG_TEST_ENV};VOXRG_PLUGIN_PATH=${VRG_LOADER_DIR}" TIMEOUT 300 SKIP_RETURN_CODE 77)
endforeach()

# The CLI: check, render, plugins, help, exit codes.
add_test(NAME cli COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/test_cli.sh $<TARGET_FILE:voxrg_cli> ${CMAKE_CURRENT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/cli_out)
set_tests_properties(cli PROPERTIES ENVIRONMENT "${VRG_TEST_ENV}" TIMEOUT 600)

# Hot reload driven from a script: `render --watch --sequence` while the test
# edits a shader, the graph and a plugin (rebuilt with cc).
add_test(NAME cli_watch COMMAND python3 ${CMAKE_CURRENT_SOURCE_DIR}/test_watch.py $<TARGET_FILE:voxrg_cli> ${CMAKE_CURRENT_SOURCE_DIR}
         ${PROJECT_SOURCE_DIR}/core/include ${CMAKE_CURRENT_BINARY_DIR}/watch_out)
set_tests_properties(cli_watch PROPERTIES ENVIRONMENT "${VRG_TEST_ENV}" TIMEOUT 600)

# Plugins as found in the wild: impostors beside a graph, truncated builds,
# garbage, a FIFO, a crashing pass, hot-reload faults under render --watch.
add_test(NAME plugin_faults COMMAND python3 ${CMAKE_CURRENT_SOURCE_DIR}/test_plugin_faults.py $<TARGET_FILE:voxrg_cli>
         ${PROJECT_SOURCE_DIR}/core/include ${CMAKE_CURRENT_BINARY_DIR}/plugin_faults_out)
set_tests_properties(plugin_faults PROPERTIES ENVIRONMENT "${VRG_TEST_ENV}" TIMEOUT 600)

# The complete pass of docs/plugin-abi.md builds and renders as the page says.
add_test(NAME docs_example COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/test_docs_example.sh $<TARGET_FILE:voxrg_cli> ${PROJECT_SOURCE_DIR}
         $<TARGET_FILE_DIR:voxrg> ${VOXRG_PLUGIN_OUTPUT_DIR} ${CMAKE_CURRENT_BINARY_DIR}/docs_example)
set_tests_properties(docs_example PROPERTIES ENVIRONMENT "${VRG_TEST_ENV}" TIMEOUT 300)

# The shipped graphs render under validation.
file(GLOB shipped_graphs ${PROJECT_SOURCE_DIR}/graphs/*.ini)
foreach(graph ${shipped_graphs})
  get_filename_component(gname ${graph} NAME_WE)
  set(extra)
  if(gname STREQUAL "reference") # 256 frames per output frame: a few suffice here
    set(extra --set converge.samples_per_frame=2)
  endif()
  add_test(NAME graph_${gname} COMMAND voxrg_cli render ${graph} --validate --frames 3 --size 96x54 ${extra} --out ${CMAKE_CURRENT_BINARY_DIR}/graph_out/${gname})
  set_tests_properties(graph_${gname} PROPERTIES ENVIRONMENT "${VRG_TEST_ENV}" TIMEOUT 300)
endforeach()

# libFuzzer: parse + validate + compile + aliasing of graph text, seeded with
# every good and bad graph; a short run in the suite, longer by hand.
if(VOXRG_FUZZ)
  if(NOT CMAKE_C_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "VOXRG_FUZZ needs clang (CC=clang)")
  endif()
  add_executable(fuzz_graph fuzz_graph.c)
  target_compile_options(fuzz_graph PRIVATE -fsanitize=fuzzer)
  target_link_options(fuzz_graph PRIVATE -fsanitize=fuzzer)
  target_link_libraries(fuzz_graph PRIVATE voxrg)
  target_compile_options(voxrg_objects PRIVATE -fsanitize=fuzzer-no-link)
  set(FUZZ_CORPUS ${CMAKE_CURRENT_BINARY_DIR}/fuzz_corpus)
  add_test(NAME fuzz_graph
           COMMAND ${CMAKE_COMMAND} -E env ${VRG_TEST_ENV}
                   sh -c "mkdir -p ${FUZZ_CORPUS} && cp ${CMAKE_CURRENT_SOURCE_DIR}/graphs/*.ini ${CMAKE_CURRENT_SOURCE_DIR}/bad/*.ini ${PROJECT_SOURCE_DIR}/graphs/*.ini ${FUZZ_CORPUS}/ && $<TARGET_FILE:fuzz_graph> -runs=20000 -max_len=4096 -timeout=10 ${FUZZ_CORPUS}")
  set_tests_properties(fuzz_graph PROPERTIES TIMEOUT 600)
  # plugin descriptors: from nothing (no seed corpus: the input is a recipe)
  add_executable(fuzz_plugin_desc fuzz_plugin_desc.c)
  target_compile_options(fuzz_plugin_desc PRIVATE -fsanitize=fuzzer)
  target_link_options(fuzz_plugin_desc PRIVATE -fsanitize=fuzzer)
  target_link_libraries(fuzz_plugin_desc PRIVATE voxrg_internal m)
  add_test(NAME fuzz_plugin_desc COMMAND ${CMAKE_COMMAND} -E env ${VRG_TEST_ENV} $<TARGET_FILE:fuzz_plugin_desc> -runs=200000 -max_len=2048)
  set_tests_properties(fuzz_plugin_desc PROPERTIES TIMEOUT 600)
  # camera paths: the parser and the curve, seeded with the shipped paths
  add_executable(fuzz_camera_path fuzz_camera_path.c)
  target_compile_options(fuzz_camera_path PRIVATE -fsanitize=fuzzer)
  target_link_options(fuzz_camera_path PRIVATE -fsanitize=fuzzer)
  target_link_libraries(fuzz_camera_path PRIVATE voxrg m)
  set(FUZZ_PATH_CORPUS ${CMAKE_CURRENT_BINARY_DIR}/fuzz_path_corpus)
  add_test(NAME fuzz_camera_path
           COMMAND sh -c "mkdir -p ${FUZZ_PATH_CORPUS} && cp ${PROJECT_SOURCE_DIR}/graphs/paths/*.path ${FUZZ_PATH_CORPUS}/ && $<TARGET_FILE:fuzz_camera_path> -runs=20000 -max_len=2048 -timeout=10 ${FUZZ_PATH_CORPUS}")
  set_tests_properties(fuzz_camera_path PROPERTIES TIMEOUT 300)
endif()

# The library exports exactly what its public headers declare.
add_test(NAME exports COMMAND python3 ${CMAKE_CURRENT_SOURCE_DIR}/check_exports.py $<TARGET_FILE:voxrg> ${PROJECT_SOURCE_DIR}/core/include)

# The loader's checks of plugin descriptors, case by case (no device).
add_executable(test_plugin_desc test_plugin_desc.c)
target_link_libraries(test_plugin_desc PRIVATE voxrg_internal m)
add_test(NAME plugin_desc COMMAND test_plugin_desc)
set_tests_properties(plugin_desc PROPERTIES ENVIRONMENT "${VRG_TEST_ENV}")

# Image metrics of voxrg compare against hand-computed values (no device).
add_executable(test_metrics test_metrics.c)
target_link_libraries(test_metrics PRIVATE voxrg m)
foreach(case psnr ssim flip temporal colors)
  add_test(NAME metrics_${case} COMMAND test_metrics ${case})
  set_tests_properties(metrics_${case} PROPERTIES ENVIRONMENT "${VRG_TEST_ENV}" LABELS "metrics")
endforeach()

# The writer of output files: a failed write keeps the old file, a commit
# replaces it whole (no device).
add_executable(test_output test_output.c)
target_link_libraries(test_output PRIVATE voxrg)
foreach(case full_disk commit dir_check)
  add_test(NAME output_${case} COMMAND test_output ${case} WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  set_tests_properties(output_${case} PROPERTIES ENVIRONMENT "${VRG_TEST_ENV}")
endforeach()

# voxrg compare end to end (metrics, cache, report, errors); then the report
# opened in headless Chromium.
add_test(NAME compare COMMAND python3 ${CMAKE_CURRENT_SOURCE_DIR}/test_compare.py $<TARGET_FILE:voxrg_cli> ${PROJECT_SOURCE_DIR}
         ${CMAKE_CURRENT_BINARY_DIR}/compare_out)
set_tests_properties(compare PROPERTIES ENVIRONMENT "${VRG_TEST_ENV}" TIMEOUT 900 FIXTURES_SETUP compare_report)
add_test(NAME compare_report_browser COMMAND python3 ${CMAKE_CURRENT_SOURCE_DIR}/test_report_browser.py
         ${CMAKE_CURRENT_BINARY_DIR}/compare_out/e2e/report.html ${CMAKE_CURRENT_BINARY_DIR}/compare_browser)
set_tests_properties(compare_report_browser PROPERTIES TIMEOUT 300 SKIP_RETURN_CODE 77 FIXTURES_REQUIRED compare_report)

# Frames in flight: rings, attribution of readbacks, stats and timings.
add_executable(test_frames_in_flight test_frames_in_flight.c)
target_link_libraries(test_frames_in_flight PRIVATE voxrg)
vrg_use_fast_malloc(test_frames_in_flight)
foreach(case ring ring_deep ring_single_frame attribution timings resize_capture timeout)
  add_test(NAME frames_in_flight_${case} COMMAND test_frames_in_flight ${case})
  set_tests_properties(frames_in_flight_${case} PROPERTIES ENVIRONMENT "${VRG_TEST_ENV}" TIMEOUT 300)
endforeach()
add_test(NAME frames_in_flight_images COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/test_frames_in_flight.sh $<TARGET_FILE:voxrg_cli> ${PROJECT_SOURCE_DIR}
         ${CMAKE_CURRENT_BINARY_DIR}/frames_in_flight_out)
set_tests_properties(frames_in_flight_images PROPERTIES ENVIRONMENT "${VRG_TEST_ENV}" TIMEOUT 600)
