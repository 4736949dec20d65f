# The dependency rules of the tree, checked on every build so that a stray include fails it
# instead of slipping in (docs/architecture.md, "Layers"):
#  - felt_core is the simulation: Eigen and the standard library, no threads, files or sockets;
#  - its haptics folder renders against any surface: it knows nothing of cloth, solids or worlds;
#  - the layers point one way: net -> runtime -> scene -> core;
#  - the client and the common libraries include nothing of the server.
# Run with -DROOT=<source tree>.

function(forbid_includes dir pattern why)
  file(GLOB_RECURSE files "${ROOT}/${dir}/*.hpp" "${ROOT}/${dir}/*.cpp")
  foreach(file IN LISTS files)
    file(STRINGS "${file}" includes REGEX "^[ \t]*#[ \t]*include")
    foreach(line IN LISTS includes)
      if(line MATCHES "${pattern}")
        file(RELATIVE_PATH name "${ROOT}" "${file}")
        message(FATAL_ERROR "${name}: '${line}': ${why}")
      endif()
    endforeach()
  endforeach()
endfunction()

set(server_layers "\"(core|scene|runtime|net)/")
forbid_includes(server/core
  "(boost/|asio|google/protobuf|\\.pb\\.h|nlohmann|json|<thread>|<mutex>|<shared_mutex>|<condition_variable>|<future>|<atomic>|<stop_token>|<fstream>|<filesystem>|<iostream>|<pthread\\.h>|<unistd\\.h>|sys/socket|netinet/|arpa/)"
  "felt_core includes Eigen and the standard library only, and no threads, files or sockets")
forbid_includes(server/core "\"(scene|runtime|net)/" "felt_core includes no layer above it")
forbid_includes(server/core/haptics "\"core/(cloth|solids|world)/"
  "the haptics folder renders against any surface and includes no cloth, solid or world")
forbid_includes(server/scene "\"(runtime|net)/" "felt_scene includes no layer above it")
forbid_includes(server/runtime "\"net/" "felt_runtime includes no layer above it")
forbid_includes(client_cpp "${server_layers}" "the client includes nothing of the server")
forbid_includes(common "${server_layers}" "the common libraries include nothing of the server")
