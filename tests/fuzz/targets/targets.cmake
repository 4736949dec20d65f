# The coverage-guided fuzz targets and what each links. tests/CMakeLists.txt builds each into a
# test that replays its committed inputs; CMakeLists.txt beside this file builds each into a
# libFuzzer binary (-DFELT_FUZZ=ON, scripts/fuzz).
set(FELT_FUZZ_TARGETS
  frame_decoder client_message scene_json thesis_config obj_reader tetgen_reader)
set(FELT_FUZZ_DIR ${CMAKE_CURRENT_LIST_DIR})

# Adds target `name`'s sources, libraries and definitions to the executable `executable`.
function(felt_fuzz_target_setup executable name)
  target_sources(${executable} PRIVATE ${FELT_FUZZ_DIR}/${name}_target.cpp)
  target_include_directories(${executable} PRIVATE ${FELT_FUZZ_DIR} ${FELT_FUZZ_DIR}/../..)
  target_compile_definitions(${executable} PRIVATE FELT_SCENE_DIR="${FELT_SCENE_DIR}")
  if(name STREQUAL "frame_decoder")
    target_link_libraries(${executable} PRIVATE felt_proto)
  elseif(name STREQUAL "client_message")
    target_sources(${executable} PRIVATE ${FELT_FUZZ_DIR}/../../net/in_process_server.cpp)
    target_link_libraries(${executable} PRIVATE felt_net felt_client)
  else()
    target_link_libraries(${executable} PRIVATE felt_scene)
  endif()
endfunction()
