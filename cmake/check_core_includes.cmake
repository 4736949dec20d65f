# felt_core is the simulation and nothing else: it may include Eigen and the standard library,
# never Asio, protobuf or JSON. Run at every build (see server/CMakeLists.txt) so that a stray
# include fails the build instead of slipping in.
file(GLOB_RECURSE core_files "${CORE_DIR}/*.hpp" "${CORE_DIR}/*.cpp")
foreach(file IN LISTS core_files)
  file(STRINGS "${file}" includes REGEX "^[ \t]*#[ \t]*include")
  foreach(line IN LISTS includes)
    if(line MATCHES "(boost/|asio|google/protobuf|\\.pb\\.h|nlohmann|json)")
      message(FATAL_ERROR "${file}: felt_core must not include '${line}' (Eigen only)")
    endif()
  endforeach()
endforeach()
