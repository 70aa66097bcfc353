# Installs ptlab::chi2: library, public header, CMake package (find_package(ptlab)), pkg-config.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS ptlab_chi2 EXPORT ptlabTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${CMAKE_SOURCE_DIR}/tools/chi2/include/ptlab/chi2.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/ptlab)
install(EXPORT ptlabTargets NAMESPACE ptlab::
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/ptlab)
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/package/ptlabConfig.cmake.in
  ${CMAKE_BINARY_DIR}/package/ptlabConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/ptlab)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/package/ptlabConfigVersion.cmake
  COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_BINARY_DIR}/package/ptlabConfig.cmake
  ${CMAKE_BINARY_DIR}/package/ptlabConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/ptlab)
# The .pc file is written at install time, so it names the prefix the package is installed to.
install(CODE "
  set(prefix \"\${CMAKE_INSTALL_PREFIX}\")
  file(WRITE \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/pkgconfig/ptlab-chi2.pc\"
\"prefix=\${prefix}
libdir=\\\${prefix}/${CMAKE_INSTALL_LIBDIR}
includedir=\\\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}

Name: ptlab-chi2
Description: ptlab's chi-square and t-test lab for samplers
Version: ${PROJECT_VERSION}
Libs: -L\\\${libdir} -lptlab_chi2
Cflags: -I\\\${includedir} -std=c++17
\")")
