# Every third-party package Tessera uses, found once. scripts/install-deps.sh
# installs them by Debian package name; each workaround says its reason beside it.
find_package(Threads REQUIRED)
find_package(glm REQUIRED)
find_package(spdlog REQUIRED)
find_package(fmt REQUIRED)

if(TSR_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(TSR_BUILD_BENCHMARKS AND NOT TSR_ONLY_SCENEGRAPH)
  find_package(benchmark REQUIRED)
endif()

if(NOT TSR_ONLY_SCENEGRAPH)
  find_package(TinyGLTF REQUIRED)
  find_package(draco CONFIG REQUIRED)  # KHR_draco_mesh_compression on import
  find_package(meshoptimizer CONFIG REQUIRED)  # EXT_meshopt_compression on import
  find_package(nlohmann_json 3 REQUIRED)
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(XXHASH REQUIRED IMPORTED_TARGET libxxhash>=0.8)  # the import cache's hashes; no CMake package in Debian
  find_package(CLI11 REQUIRED)
  find_package(TBB REQUIRED COMPONENTS tbb)
  find_package(embree 3 REQUIRED)
  find_package(Eigen3 3.3 REQUIRED NO_MODULE)  # temporal PCA (backends/temporal)
  find_package(OpenImageIO REQUIRED)
  include(${CMAKE_CURRENT_LIST_DIR}/TesseraFixOpenImageIO.cmake)
endif()
