# plab_add_contact_model(NAME src...) / plab_add_plugin(NAME src...):
# one shared library per plug-in, named plab_<NAME>.so, placed where the
# host looks for it. Plug-ins see only the public API (core/include/plab).
function(plab_add_plugin name)
  add_library(plab_${name} MODULE ${ARGN})
  target_link_libraries(plab_${name} PRIVATE plab::api)
  set_target_properties(plab_${name} PROPERTIES PREFIX "" OUTPUT_NAME plab_${name}
    LIBRARY_OUTPUT_DIRECTORY ${PLAB_PLUGIN_OUTPUT_DIR})
  # `plab` depends on every in-tree plug-in (see scripting/CMakeLists.txt)
  set_property(GLOBAL APPEND PROPERTY PLAB_IN_TREE_PLUGINS plab_${name})
endfunction()

function(plab_add_contact_model name)
  plab_add_plugin(${name} ${ARGN})
endfunction()
