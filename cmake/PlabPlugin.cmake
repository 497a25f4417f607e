# plab_add_contact_model(NAME src...) / plab_add_plugin(NAME src...):
# one shared library per plug-in, named plab_<NAME>.so, placed where the
# host looks for it. Plug-ins see only the public API (core/include/plab).
#
# The same file serves the ParticleLab build (in tree) and out-of-tree
# projects through find_package(ParticleLab) (installed SDK). Out of tree the
# library lands in PLAB_PLUGIN_OUTPUT_DIR, by default the project's build
# folder: point plab at it with PLAB_PLUGIN_PATH or a path in the scene.
if(NOT DEFINED PLAB_PLUGIN_OUTPUT_DIR)
  set(PLAB_PLUGIN_OUTPUT_DIR ${CMAKE_BINARY_DIR})
endif()

function(plab_add_plugin name)
  add_library(plab_${name} MODULE ${ARGN})
  target_link_libraries(plab_${name} PRIVATE plab::api)
  target_compile_features(plab_${name} PRIVATE cxx_std_17)
  # a law's sqrt needs no errno (no test and library call after each one);
  # the adapter's loop over a batch (contact_model.hpp) vectorises a law's
  # choices only when both sides may be evaluated (no trapping maths: the
  # results are the same, only floating-point exception flags are not
  # kept), and its clones for each CPU give the scalar law's bits only
  # without FMA contraction
  target_compile_options(plab_${name} PRIVATE
    $<$<CXX_COMPILER_ID:GNU,Clang>:-fno-math-errno -fno-trapping-math -ffp-contract=off>)
  # only the two entry points (PLAB_PLUGIN) are exported
  set_target_properties(plab_${name} PROPERTIES PREFIX "" OUTPUT_NAME plab_${name}
    LIBRARY_OUTPUT_DIRECTORY ${PLAB_PLUGIN_OUTPUT_DIR}
    CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
  if(PLAB_IN_TREE)
    # `plab` depends on every in-tree plug-in (see scripting/CMakeLists.txt)
    set_property(GLOBAL APPEND PROPERTY PLAB_IN_TREE_PLUGINS plab_${name})
    install(TARGETS plab_${name} LIBRARY DESTINATION ${PLAB_INSTALL_PLUGIN_DIR})
  endif()
endfunction()

function(plab_add_contact_model name)
  plab_add_plugin(${name} ${ARGN})
endfunction()
