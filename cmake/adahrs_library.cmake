# adahrs_library(NAME <folder> DEPS <targets...>)
# One library target per source folder, named adahrs_<folder>, built from every .cc below the
# folder. Dependencies are listed explicitly so that the one-way layering is visible here:
# apps -> calib -> hil -> firmware_model / sensor_sim; rig_sim -> hil + sensor_sim + firmware_model.
function(adahrs_library)
  cmake_parse_arguments(ARG "" "NAME" "DEPS" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
  set(target adahrs_${ARG_NAME})
  if(sources)
    add_library(${target} STATIC ${sources})
    target_include_directories(${target} PUBLIC ${PROJECT_SOURCE_DIR})
    target_link_libraries(${target} PUBLIC ${ARG_DEPS})
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE ${PROJECT_SOURCE_DIR})
    target_link_libraries(${target} INTERFACE ${ARG_DEPS})
  endif()
endfunction()
