# `cmake --install build --prefix P`: the carbonmesh binary, the module libraries, their public headers and a
# package config, so that find_package(carbonmesh) and target_link_libraries(app carbonmesh::remesh) work.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(CARBONMESH_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/carbonmesh)

# carbonmesh_install_module(<target>): installs a module library and its include/ folder.
function(carbonmesh_install_module target)
  install(TARGETS ${target} EXPORT carbonmeshTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  get_target_property(source_dir ${target} SOURCE_DIR)
  install(DIRECTORY ${source_dir}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

function(carbonmesh_install_package)
  install(EXPORT carbonmeshTargets NAMESPACE carbonmesh:: DESTINATION ${CARBONMESH_INSTALL_CMAKEDIR})
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/carbonmeshConfig.cmake.in
    ${PROJECT_BINARY_DIR}/carbonmeshConfig.cmake INSTALL_DESTINATION ${CARBONMESH_INSTALL_CMAKEDIR})
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/carbonmeshConfigVersion.cmake
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/carbonmeshConfig.cmake ${PROJECT_BINARY_DIR}/carbonmeshConfigVersion.cmake
    ${PROJECT_SOURCE_DIR}/cmake/FindGLPK.cmake
    DESTINATION ${CARBONMESH_INSTALL_CMAKEDIR})
endfunction()
