# Every dependency is a Debian package (tools/setup.sh installs them); nothing is downloaded.
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)
find_package(Vulkan REQUIRED)
find_package(glslang REQUIRED CONFIG)
find_package(glm REQUIRED CONFIG)
find_package(OpenEXR REQUIRED CONFIG)
find_package(PNG REQUIRED)
find_package(GTest REQUIRED)
find_package(nlohmann_json REQUIRED CONFIG)
pkg_check_modules(LUA REQUIRED IMPORTED_TARGET lua5.4)
pkg_check_modules(HTTPLIB REQUIRED IMPORTED_TARGET cpp-httplib)  # rgraph serve
pkg_check_modules(XXHASH REQUIRED IMPORTED_TARGET libxxhash)  # graph/core/hash.h
pkg_check_modules(SPIRV_CROSS REQUIRED IMPORTED_TARGET spirv-cross-c-shared)

if(NOT EXISTS /usr/include/tiny_gltf.h)
  message(FATAL_ERROR "tiny_gltf.h not found: install libtinygltf-dev (tools/setup.sh does)")
endif()
if(NOT EXISTS /usr/include/stb/stb_image.h)
  message(FATAL_ERROR "stb_image.h not found: install libstb-dev (tools/setup.sh does)")
endif()
