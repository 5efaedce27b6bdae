# The consumer_core_serial test (cmake -P), items "a lean core" and "library-only install" of
# issue 22, as a new user would try them:
#   1. configure antcd with Eigen alone visible (oneTBB, assimp, tinyobjloader, nlohmann-json
#      hidden): the core must configure on its own;
#   2. configure a build with the defaults (tools, Python module and optional libraries on) but
#      oneTBB off, build ONLY the core target, `cmake --install` it: every install rule of a part
#      that was not built must be skipped;
#   3. build tests/consumer against that prefix as a core-only user and run it: the serial core
#      must give the same digest of answers as the oneTBB build (DIGEST, written by
#      consumer_build_and_run).
# Variables: SOURCE (antcd's source folder), WORK (a scratch folder), GENERATOR, BUILD_TYPE,
# CXX_COMPILER, CXX_FLAGS, LINKER_FLAGS, LAUNCHER (e.g. ccache, may be empty), DIGEST.
foreach(_var SOURCE WORK GENERATOR BUILD_TYPE CXX_COMPILER DIGEST)
  if(NOT DEFINED ${_var})
    message(FATAL_ERROR "consumer_core.cmake: -D${_var}=... is missing")
  endif()
endforeach()

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    string(REPLACE ";" " " command "${ARGN}")
    message(FATAL_ERROR "consumer_core: failed (${status}): ${command}")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK})
set(common -G ${GENERATOR} -DCMAKE_BUILD_TYPE=${BUILD_TYPE} -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
           "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${LINKER_FLAGS}"
           "-DCMAKE_SHARED_LINKER_FLAGS=${LINKER_FLAGS}" "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}")

message(STATUS "consumer_core: 1. configure with Eigen alone")
run(${CMAKE_COMMAND} -S ${SOURCE} -B ${WORK}/eigen-only ${common}
    -DCMAKE_DISABLE_FIND_PACKAGE_TBB=ON -DCMAKE_DISABLE_FIND_PACKAGE_assimp=ON
    -DCMAKE_DISABLE_FIND_PACKAGE_tinyobjloader=ON -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON)

message(STATUS "consumer_core: 2. build the core alone without oneTBB, install it")
run(${CMAKE_COMMAND} -S ${SOURCE} -B ${WORK}/build ${common} -DANTCD_USE_TBB=OFF
    -DANTCD_BUILD_TESTS=OFF -DANTCD_BUILD_BENCHMARKS=OFF -DANTCD_BUILD_LEARNED=OFF
    -DANTCD_BUILD_VIEWER=OFF)
cmake_host_system_information(RESULT cores QUERY NUMBER_OF_LOGICAL_CORES)
run(${CMAKE_COMMAND} --build ${WORK}/build --target antcd -j ${cores})
run(${CMAKE_COMMAND} --install ${WORK}/build --prefix ${WORK}/prefix)
file(GLOB _absent ${WORK}/prefix/bin/antcd* ${WORK}/prefix/lib*/libantcd_*
     ${WORK}/prefix/lib*/python*/*/antcd)
if(_absent)
  message(FATAL_ERROR "consumer_core: installed but not built: ${_absent}")
endif()

message(STATUS "consumer_core: 3. a core-only consumer, digest compared with the oneTBB build's")
run(${CMAKE_COMMAND} -S ${SOURCE}/tests/consumer -B ${WORK}/consumer ${common}
    -DCMAKE_PREFIX_PATH=${WORK}/prefix -DANTCD_CONSUMER_PARTS=core)
run(${CMAKE_COMMAND} --build ${WORK}/consumer)
run(${WORK}/consumer/antcd_consumer --expect-digest ${DIGEST})
