# Included by the top-level CMakeLists.txt: builds wasm/ (the npm package `antcd`) with Emscripten
# when emcmake is found, as the target antcd_wasm (part of ALL). The inner project lives in
# <build>/wasm, is configured once (emcmake cmake) and rebuilt incrementally by every build; its
# products go to wasm/dist/ in the sources, where `npm pack` in wasm/ picks them up.
# -DANTCD_BUILD_WASM=OFF skips it. Emscripten's JS optimiser needs Debian's node-acorn, which a
# node that is not Debian's finds only through NODE_PATH=/usr/share/nodejs (set here).
option(ANTCD_BUILD_WASM "Build the WebAssembly package in wasm/ when Emscripten (emcmake) is found" ON)

set(ANTCD_WASM_DIST "")
if(NOT ANTCD_BUILD_WASM)
  message(STATUS "antcd: WebAssembly package disabled (ANTCD_BUILD_WASM=OFF)")
  return()
endif()
find_program(ANTCD_EMCMAKE emcmake)
if(NOT ANTCD_EMCMAKE)
  message(STATUS "antcd: emcmake not found: WebAssembly package (wasm/) not built "
                 "(scripts/install-deps.sh installs Debian's emscripten)")
  return()
endif()

set(_src ${PROJECT_SOURCE_DIR}/wasm)
set(_bin ${PROJECT_BINARY_DIR}/wasm)
set(ANTCD_WASM_DIST ${_src}/dist)
set(_env ${CMAKE_COMMAND} -E env NODE_PATH=/usr/share/nodejs)
set(_launcher "")
if(CMAKE_CXX_COMPILER_LAUNCHER)
  set(_launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER})
endif()
add_custom_command(
  OUTPUT ${_bin}/CMakeCache.txt
  COMMAND ${_env} ${ANTCD_EMCMAKE} ${CMAKE_COMMAND} -S ${_src} -B ${_bin} -DCMAKE_BUILD_TYPE=Release
          -DANTCD_WASM_PACKAGE_DIR=${ANTCD_WASM_DIST} ${_launcher}
  DEPENDS ${_src}/CMakeLists.txt ${PROJECT_SOURCE_DIR}/src/core_sources.cmake
  COMMENT "emcmake: configuring the WebAssembly build (wasm/)"
  VERBATIM)
add_custom_target(antcd_wasm ALL
  COMMAND ${_env} ${CMAKE_COMMAND} --build ${_bin} -j 2
  DEPENDS ${_bin}/CMakeCache.txt
  BYPRODUCTS ${ANTCD_WASM_DIST}/antcd_core.cjs ${ANTCD_WASM_DIST}/antcd_core.wasm
  COMMENT "emscripten: building the npm package antcd (wasm/dist)"
  VERBATIM)

# The native side of the node benchmark (wasm/bench/bench.mjs): reference verdicts and times.
if(TARGET antcd_io)
  add_executable(antcd_wasm_bench_native ${PROJECT_SOURCE_DIR}/wasm/bench/native_collide.cpp)
  target_link_libraries(antcd_wasm_bench_native PRIVATE antcd antcd_io)
  antcd_set_warnings(antcd_wasm_bench_native)
endif()
