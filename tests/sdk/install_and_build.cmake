# The SDK as a user gets it: install ParticleLab into a fresh prefix, compile
# each package header it installs on its own, build the Hertz tutorial
# project and a `plab new-model` skeleton against it (no access to the source
# tree's headers or build), and run their tests, which load the libraries
# into the *installed* plab. Debug: compiles in half the time.
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -P install_and_build.cmake
cmake_minimum_required(VERSION 3.20)  # (script mode: the policies of the project's CMake)
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

# The packages' support headers are part of the SDK (physics/<package>/include):
# each installed, and each compiling on its own in a project that has the
# installed SDK only (one source file per header, the header its only include).
set(headers_src ${WORK_DIR}/headers_src)
file(MAKE_DIRECTORY ${headers_src})
file(GLOB package_headers RELATIVE ${prefix}/include ${prefix}/include/plab/*/*.hpp)
foreach(required plab/sph/kernels.hpp plab/sph/law.hpp plab/sph/material.hpp plab/dem/linear_law.hpp
                 plab/coupling/drag_law.hpp)
  if(NOT required IN_LIST package_headers)
    message(FATAL_ERROR "the SDK installed into ${prefix} has no include/${required}; it has: ${package_headers}")
  endif()
endforeach()
set(sources)
foreach(header ${package_headers})
  string(MAKE_C_IDENTIFIER ${header} id)
  set(body "#include <${header}>\n")
  if(header STREQUAL "plab/sph/kernels.hpp")  # and usable: W(0) of the Wendland kernel in 2D
    string(APPEND body "double ${id}_w0() { return plab::sph::Kernel{plab::sph::KernelKind::wendland_c2, 2, 0.01}.value(0.0); }\n")
  endif()
  file(WRITE ${headers_src}/${id}.cpp "${body}")
  list(APPEND sources ${id}.cpp)
endforeach()
string(REPLACE ";" " " sources "${sources}")
file(WRITE ${headers_src}/CMakeLists.txt "cmake_minimum_required(VERSION 3.20)
project(plab_sdk_headers LANGUAGES CXX)
find_package(ParticleLab REQUIRED)
add_library(plab_sdk_headers OBJECT ${sources})
target_link_libraries(plab_sdk_headers PRIVATE plab::api)
target_compile_features(plab_sdk_headers PRIVATE cxx_std_17)
")
run(${CMAKE_COMMAND} -S ${headers_src} -B ${WORK_DIR}/headers_build -DCMAKE_BUILD_TYPE=Debug -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/headers_build -j2)

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
