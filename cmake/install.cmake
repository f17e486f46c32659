# What `cmake --install build --prefix P` adds beyond the targets' own
# install() rules: the data of share/voxrg and the SDK's package files.
# Nothing installed names the source or build tree: the runtime finds
# P/lib/voxrg/plugins and P/share/voxrg from libvoxrg's own location.
include(CMakePackageConfigHelpers)
set(VRG_INSTALL_INCLUDEDIR include)
set(VRG_INSTALL_PLUGINDIR lib/voxrg/plugins)
set(VRG_INSTALL_DATADIR share/voxrg)

# the shared GLSL (shaders/include/*.glsl, the viewer's display.comp), the
# shipped graphs and their camera paths
install(DIRECTORY shaders/ DESTINATION ${VRG_INSTALL_DATADIR}/shaders)
install(DIRECTORY graphs/ DESTINATION ${VRG_INSTALL_DATADIR}/graphs)

install(EXPORT voxrgTargets NAMESPACE voxrg:: DESTINATION lib/cmake/voxrg)
configure_package_config_file(cmake/voxrgConfig.cmake.in ${CMAKE_BINARY_DIR}/pkg/voxrgConfig.cmake
  INSTALL_DESTINATION lib/cmake/voxrg
  PATH_VARS VRG_INSTALL_INCLUDEDIR VRG_INSTALL_PLUGINDIR VRG_INSTALL_DATADIR)
# 0.x: a minor version may change the ABI (VRG_ABI_VERSION), so only the
# same MAJOR.MINOR is compatible
write_basic_package_version_file(${CMAKE_BINARY_DIR}/pkg/voxrgConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/pkg/voxrgConfig.cmake ${CMAKE_BINARY_DIR}/pkg/voxrgConfigVersion.cmake
  cmake/voxrgAddPass.cmake DESTINATION lib/cmake/voxrg)

configure_file(cmake/voxrg.pc.in ${CMAKE_BINARY_DIR}/pkg/voxrg.pc @ONLY)
configure_file(cmake/voxrg-voxel.pc.in ${CMAKE_BINARY_DIR}/pkg/voxrg-voxel.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/pkg/voxrg.pc ${CMAKE_BINARY_DIR}/pkg/voxrg-voxel.pc DESTINATION lib/pkgconfig)
