# The CLI and scripts around it (included from tests/CMakeLists.txt).

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
