# Install rules: the `idbench` executable, the libraries with their public
# headers (include/idbench/<module>/) and a CMake package, so that
# find_package(idbench) gives idbench::engine, idbench::logs, idbench::ident, ...
include(CMakePackageConfigHelpers)

install(TARGETS idbench_engine idbench_logs idbench_ident idbench_excitation idbench_render idbench_osmesa idbench_workbench
        EXPORT idbenchTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(module engine logs ident excitation render workbench)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${module}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()
install(TARGETS idbench RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The built-in robots are compiled in; paper6r's URDF is installed as an example robot file.
install(FILES ${PROJECT_SOURCE_DIR}/engine/robots/paper6r.urdf DESTINATION ${CMAKE_INSTALL_DATADIR}/idbench/robots)
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR})

set(IDBENCH_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/idbench)
install(EXPORT idbenchTargets NAMESPACE idbench:: DESTINATION ${IDBENCH_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/idbenchConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/idbenchConfig.cmake INSTALL_DESTINATION ${IDBENCH_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/idbenchConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/idbenchConfig.cmake ${PROJECT_BINARY_DIR}/idbenchConfigVersion.cmake
        DESTINATION ${IDBENCH_CMAKE_DIR})
