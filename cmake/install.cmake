# `cmake --install`: the public headers, the static libraries, the CLI and a CMake package, so
# that a project writes find_package(stochtex) and links stochtex::runtime (load, evaluate,
# render), stochtex::analysis (build models), stochtex::io (image files), stochtex::gl when built,
# or stochtex::stochtex (analysis and io). tests/install is such a project.
include(CMakePackageConfigHelpers)

set(STOCHTEX_PACKAGE_COMPONENTS runtime analysis io)
if(STOCHTEX_BUILD_GL)
  list(APPEND STOCHTEX_PACKAGE_COMPONENTS gl)
endif()
set(STOCHTEX_PACKAGE_LIBRARIES stochtex_all)
foreach(component ${STOCHTEX_PACKAGE_COMPONENTS})
  set_target_properties(stochtex_${component} PROPERTIES EXPORT_NAME ${component})
  list(APPEND STOCHTEX_PACKAGE_LIBRARIES stochtex_${component})
endforeach()
set_target_properties(stochtex_all PROPERTIES EXPORT_NAME stochtex)

install(TARGETS ${STOCHTEX_PACKAGE_LIBRARIES} EXPORT stochtexTargets
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS stochtex)
if(STOCHTEX_BUILD_GL)
  install(DIRECTORY include/stochtex TYPE INCLUDE)
else()
  install(DIRECTORY include/stochtex TYPE INCLUDE PATTERN gpu.hpp EXCLUDE)
endif()

set(STOCHTEX_PACKAGE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/stochtex)
install(EXPORT stochtexTargets NAMESPACE stochtex:: DESTINATION ${STOCHTEX_PACKAGE_DIR})
configure_package_config_file(cmake/stochtexConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/stochtexConfig.cmake
                              INSTALL_DESTINATION ${STOCHTEX_PACKAGE_DIR})
# 0.x: a minor version may change the API, so only the same minor version is compatible.
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/stochtexConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/stochtexConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/stochtexConfigVersion.cmake
        DESTINATION ${STOCHTEX_PACKAGE_DIR})
