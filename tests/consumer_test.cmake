# Configures, builds and runs tests/consumer against rangefill: with -DMODE=install, installed into
# a scratch prefix; with -DMODE=build, the build tree itself (rangefill_DIR=<build>).
# Arguments: -DBINARY_DIR=<rangefill build> -DSOURCE_DIR=<rangefill source> -DWORK_DIR=<scratch>
# -DCOMPILER=<C++ compiler of the consumer> -DFLAGS=<its compiler and linker flags, may be empty>
file(REMOVE_RECURSE ${WORK_DIR})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed (${result}): ${ARGN}\n${output}")
  endif()
endfunction()
if(MODE STREQUAL "install")
  run(${CMAKE_COMMAND} --install ${BINARY_DIR} --prefix ${WORK_DIR}/prefix --component Unspecified)
  set(where -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix)
elseif(MODE STREQUAL "build")
  set(where -Drangefill_DIR=${BINARY_DIR})
else()
  message(FATAL_ERROR "MODE must be install or build, not '${MODE}'")
endif()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer -B ${WORK_DIR}/build
    ${where} -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${COMPILER}
    "-DCMAKE_CXX_FLAGS=${FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${FLAGS}")
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer)
