# `cmake --install build --prefix DIR`: the libraries as the CMake package
# Reeve (find_package(Reeve 0.2), targets Reeve::engine, ::cable, ::scene,
# ::render), their public headers, the `reeve` program, and the shipped
# scenes with their schema in share/reeve/scenes. README, "Using Reeve from
# another CMake project".
include(CMakePackageConfigHelpers)
set(REEVE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Reeve)
set(REEVE_INSTALL_SCENES_DIR ${CMAKE_INSTALL_DATADIR}/reeve/scenes)

install(TARGETS reeve_engine reeve_cable reeve_scene reeve_render EXPORT ReeveTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(dir engine/include cable/include scenes/include render/include)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()
install(TARGETS reeve RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
file(GLOB REEVE_SHIPPED_SCENES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/scenes/*.json)
install(FILES ${REEVE_SHIPPED_SCENES} DESTINATION ${REEVE_INSTALL_SCENES_DIR})
# The viewer's pages (`reeve run --html`'s replay, `reeve view`'s live
# page), with the three.js files they use, where the installed program
# looks: PREFIX/share/reeve/viewer.
set(REEVE_VIEWER_DIR ${CMAKE_INSTALL_DATADIR}/reeve/viewer)
install(FILES ${PROJECT_SOURCE_DIR}/viewer/replay.html ${PROJECT_SOURCE_DIR}/viewer/replay.js
              ${PROJECT_SOURCE_DIR}/viewer/view3d.js ${PROJECT_SOURCE_DIR}/viewer/live.html
              ${PROJECT_SOURCE_DIR}/viewer/live.js
        DESTINATION ${REEVE_VIEWER_DIR})
install(FILES ${PROJECT_SOURCE_DIR}/viewer/node_modules/three/build/three.module.min.js
        DESTINATION ${REEVE_VIEWER_DIR}/node_modules/three/build OPTIONAL)
install(FILES ${PROJECT_SOURCE_DIR}/viewer/node_modules/three/examples/jsm/controls/OrbitControls.js
        DESTINATION ${REEVE_VIEWER_DIR}/node_modules/three/examples/jsm/controls OPTIONAL)

install(EXPORT ReeveTargets NAMESPACE Reeve:: DESTINATION ${REEVE_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/ReeveConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/ReeveConfig.cmake
                              INSTALL_DESTINATION ${REEVE_CMAKE_DIR}
                              PATH_VARS REEVE_INSTALL_SCENES_DIR)
# 0.x: a new minor version may change the API, so 0.2 accepts 0.2.* only.
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/ReeveConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/ReeveConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/ReeveConfigVersion.cmake
        DESTINATION ${REEVE_CMAKE_DIR})
