# The SDK as a user gets it: install ParticleLab into a fresh prefix, build
# the Hertz tutorial project and a `plab new-model` skeleton against it (no
# access to the source tree's headers or build), and run their tests, which
# load the libraries into the *installed* plab. Debug: compiles in half the time.
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -P install_and_build.cmake
foreach(v BUILD_DIR SOURCE_DIR WORK_DIR)
  if(NOT ${v})
    message(FATAL_ERROR "set -D${v}=...")
  endif()
endforeach()

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "failed (${rc}): ${cmd}\n${out}\n${err}")
  endif()
  message("${out}")
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
# The built-in plug-ins must be found beside the installed plab, not in the build.
execute_process(COMMAND ${prefix}/bin/plab plugins OUTPUT_VARIABLE listing RESULT_VARIABLE rc)
string(FIND "${listing}" "${prefix}/lib/plab/plugins/plab_linear.so" at)
if(NOT rc EQUAL 0 OR at EQUAL -1)
  message(FATAL_ERROR "the installed plab does not list its own plug-ins:\n${listing}")
endif()

foreach(project hertz skeleton)
  if(project STREQUAL hertz)
    set(src ${SOURCE_DIR}/examples/teaching/hertz_model)
  else()
    set(src ${WORK_DIR}/skeleton_src)
    run(${prefix}/bin/plab new-model my_model ${src})
  endif()
  set(bin ${WORK_DIR}/${project}_build)
  run(${CMAKE_COMMAND} -S ${src} -B ${bin} -DCMAKE_BUILD_TYPE=Debug -DCMAKE_PREFIX_PATH=${prefix})
  run(${CMAKE_COMMAND} --build ${bin} -j2)
  run(${CMAKE_CTEST_COMMAND} --test-dir ${bin} --output-on-failure -V)
endforeach()
