# One static library per core folder ("layer"), each compiled against a view
# of the source tree that holds only its own folder and the folders below it
# (docs/architecture.md). An #include of a higher layer is then "No such file"
# at compile time: the build enforces the layering.
#
#   storey_layer(<folder> [DEPS <folders it uses directly>] SOURCES <files...>)
#
# creates target storey_<folder>, linked PUBLIC to storey_<dep> for each DEPS
# entry; the layers a dep itself uses come along (its closure). A DEPS entry
# must be declared before (lower layers first in core/CMakeLists.txt).
function(storey_layer name)
  cmake_parse_arguments(L "" "" "DEPS;SOURCES" ${ARGN})
  set(target storey_${name})
  add_library(${target} STATIC ${L_SOURCES})
  set(closure ${name})
  foreach(dep IN LISTS L_DEPS)
    get_property(dep_closure GLOBAL PROPERTY STOREY_LAYER_CLOSURE_${dep})
    if(NOT dep_closure)
      message(FATAL_ERROR "layer '${name}' uses '${dep}', which is not declared before it: "
                          "a layer may only use the layers below it (docs/architecture.md)")
    endif()
    list(APPEND closure ${dep_closure})
    target_link_libraries(${target} PUBLIC storey_${dep})
  endforeach()
  list(REMOVE_DUPLICATES closure)
  set_property(GLOBAL PROPERTY STOREY_LAYER_CLOSURE_${name} ${closure})
  set_property(GLOBAL APPEND PROPERTY STOREY_LAYERS ${name})

  # The view: <build>/layers/<name>/<folder> -> core/<folder> for the closure.
  set(view "${PROJECT_BINARY_DIR}/layers/${name}")
  file(REMOVE_RECURSE "${view}")
  file(MAKE_DIRECTORY "${view}")
  foreach(folder IN LISTS closure)
    file(CREATE_LINK "${PROJECT_SOURCE_DIR}/core/${folder}" "${view}/${folder}" SYMBOLIC)
  endforeach()
  set_property(GLOBAL PROPERTY STOREY_LAYER_VIEW_${name} "${view}")
  target_include_directories(${target} PRIVATE "${view}")
  target_link_libraries(${target} PUBLIC Eigen3::Eigen)
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  storey_warnings(${target})
endfunction()

# storey_layer_objects(<layer> <object library>): an OBJECT library (e.g. the
# one file that includes CGAL) compiled against its layer's view and linked
# into it.
function(storey_layer_objects name objects)
  get_property(view GLOBAL PROPERTY STOREY_LAYER_VIEW_${name})
  target_include_directories(${objects} PRIVATE "${view}")
  target_link_libraries(${objects} PRIVATE Eigen3::Eigen)
  set_target_properties(${objects} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  storey_warnings(${objects})
  target_sources(storey_${name} PRIVATE $<TARGET_OBJECTS:${objects}>)
endfunction()
