# `cmake --install`: the programs, the libraries with their headers, and a
# CMake package so another project can
#   find_package(Tessera)
#   target_link_libraries(app PRIVATE Tessera::scenegraph Tessera::mediators Tessera::embree)
# CPack turns the same install into a .deb (cpack -G DEB in the build folder).
# Included last by the top-level CMakeLists, when every layer's targets exist.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The static and header-only libraries of the library layers (every folder the top-level
# CMakeLists adds, apps aside), each exported as Tessera::NAME for its target
# tsr_NAME: a back-end added to TSR_BACKENDS is installed without a list here.
function(tsr_collect_libraries dir out)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  get_property(children DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  set(found ${${out}})
  foreach(target IN LISTS targets)
    get_target_property(type ${target} TYPE)
    if(type MATCHES "^(STATIC|INTERFACE)_LIBRARY$" AND target MATCHES "^tsr_")
      list(APPEND found ${target})
    endif()
  endforeach()
  foreach(child IN LISTS children)
    file(RELATIVE_PATH relative ${PROJECT_SOURCE_DIR} ${child})
    if(NOT relative MATCHES "^(apps|tests)(/|$)")
      tsr_collect_libraries(${child} found)
    endif()
  endforeach()
  set(${out} ${found} PARENT_SCOPE)
endfunction()
set(tsr_libraries "")
tsr_collect_libraries(${PROJECT_SOURCE_DIR} tsr_libraries)

set(tsr_exported "")
set(tsr_mediator_libs "")
foreach(target IN LISTS tsr_libraries)
  string(REGEX REPLACE "^tsr_" "" name ${target})
  list(APPEND tsr_exported ${target})
  if(target MATCHES "^tsr_mediator_")
    list(APPEND tsr_mediator_libs ${target})
  endif()
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  add_library(Tessera::${name} ALIAS ${target})
  # Layers name their include folder by absolute source path; installed, it is include/.
  get_target_property(dirs ${target} INTERFACE_INCLUDE_DIRECTORIES)
  set(interface "")
  foreach(dir IN LISTS dirs)
    if(dir MATCHES "^\\$<")
      list(APPEND interface "${dir}")
    else()
      list(APPEND interface "$<BUILD_INTERFACE:${dir}>")
      install(DIRECTORY ${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h")
    endif()
  endforeach()
  list(APPEND interface "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>")
  set_property(TARGET ${target} PROPERTY INTERFACE_INCLUDE_DIRECTORIES "${interface}")
endforeach()

# Tessera::mediators: the mediator core and every back-end's mediator this
# build has (each offers med::registerXxx(registry)).
add_library(tsr_mediators INTERFACE)
target_link_libraries(tsr_mediators INTERFACE ${tsr_mediator_libs})
set_target_properties(tsr_mediators PROPERTIES EXPORT_NAME mediators)
add_library(Tessera::mediators ALIAS tsr_mediators)
list(APPEND tsr_exported tsr_mediators)

install(TARGETS ${tsr_exported} EXPORT TesseraTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})

# Programs, as many as this build has (the viewer and the wall included when they exist).
foreach(program IN ITEMS tessera-render tessera-node tessera-inspect tessera-launch tessera-anaglyph tessera-viewer
                         tessera-wall tessera-cull)
  if(TARGET ${program})
    install(TARGETS ${program} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endif()
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/configs/ DESTINATION ${CMAKE_INSTALL_DATADIR}/tessera/configs)
# tessera-cull's page and the parts of three.js it loads (npm ci put them in
# web/node_modules); an installed tessera-cull finds them beside its bin/.
if(TARGET tessera-cull)
  set(tsr_web_dest ${CMAKE_INSTALL_DATADIR}/tessera/web)
  install(FILES ${PROJECT_SOURCE_DIR}/web/index.html DESTINATION ${tsr_web_dest})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/web/src DESTINATION ${tsr_web_dest})
  install(FILES ${PROJECT_SOURCE_DIR}/web/node_modules/three/build/three.module.js
          DESTINATION ${tsr_web_dest}/node_modules/three/build OPTIONAL)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/web/node_modules/three/examples/jsm
          DESTINATION ${tsr_web_dest}/node_modules/three/examples OPTIONAL)
endif()

set(tsr_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/Tessera)
# What the config must find again: the static libraries' own dependencies.
if(TARGET tsr_vulkan)
  set(TSR_PACKAGE_HAS_VULKAN ON)
else()
  set(TSR_PACKAGE_HAS_VULKAN OFF)
endif()
if(TARGET tsr_cluster)
  set(TSR_PACKAGE_HAS_CLUSTER ON)
else()
  set(TSR_PACKAGE_HAS_CLUSTER OFF)
endif()
install(EXPORT TesseraTargets NAMESPACE Tessera:: DESTINATION ${tsr_cmake_dir})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/TesseraConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/TesseraConfig.cmake INSTALL_DESTINATION ${tsr_cmake_dir})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/TesseraConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/TesseraConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/TesseraConfigVersion.cmake
        DESTINATION ${tsr_cmake_dir})

# cpack -G DEB: one package with programs and development files; run-time
# library dependencies come from dpkg-shlibdeps, the headers' from the list.
set(CPACK_PACKAGE_NAME tessera)
set(CPACK_PACKAGE_VENDOR "Tessera")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Distributed rendering with exchangeable back-ends (Embree, Vulkan, coverage)")
set(CPACK_PACKAGE_CONTACT "Tessera developers <tessera@example.org>")
set(CPACK_GENERATOR DEB)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "libglm-dev, libspdlog-dev, libfmt-dev, libembree-dev, libtbb-dev, libvulkan-dev, libglfw3-dev, libtinygltf-dev, libdraco-dev, libmeshoptimizer-dev, libxxhash-dev, \
nlohmann-json3-dev, libopenimageio-dev, libeigen3-dev, libboost-dev, libssl-dev, liblz4-dev, libzstd-dev, pkg-config")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)  # debug information would make the package several times larger
include(CPack)
