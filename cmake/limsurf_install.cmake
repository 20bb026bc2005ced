# Install rules and the package config for find_package(limsurf).
include(CMakePackageConfigHelpers)

install(TARGETS limsurf_subdiv limsurf_umbrella
    EXPORT limsurfTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/limsurf DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
if(TARGET limsurf_cli)
    install(TARGETS limsurf_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

set(LIMSURF_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/limsurf)
install(EXPORT limsurfTargets NAMESPACE limsurf:: DESTINATION ${LIMSURF_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/limsurf-config.cmake.in
    ${PROJECT_BINARY_DIR}/limsurf-config.cmake INSTALL_DESTINATION ${LIMSURF_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/limsurf-config-version.cmake
    COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/limsurf-config.cmake ${PROJECT_BINARY_DIR}/limsurf-config-version.cmake
    DESTINATION ${LIMSURF_CMAKE_DIR})
