# The dependency rules of the tree, checked on every build so that a stray include fails it
# instead of slipping in (docs/architecture.md, "Layers"):
#  - felt_core is the simulation: Eigen, the standard library and felt_ids, no threads, files or
#    sockets;
#  - the layers point one way: net -> runtime -> scene -> core;
#  - felt_haptics (core/{math,geometry,collision,haptics} but the particle collider), which the
#    client links too, includes nothing else of the core;
#  - the client and the common libraries include nothing of the server but felt_haptics.
# Run with -DROOT=<source tree>.

# An optional fourth argument names files of `dir` the rule leaves out (a regular expression).
function(forbid_includes dir pattern why)
  file(GLOB_RECURSE files "${ROOT}/${dir}/*.hpp" "${ROOT}/${dir}/*.cpp")
  if(ARGC GREATER 3)
    list(FILTER files EXCLUDE REGEX "${ARGV3}")
  endif()
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
forbid_includes(server/core "\"(device|scheduling|mesh_files|command_line)/"
  "felt_core uses nothing of common/ but its ids (felt_ids)")
forbid_includes(server/scene "\"(runtime|net)/" "felt_scene includes no layer above it")
forbid_includes(server/runtime "\"net/" "felt_runtime includes no layer above it")
set(not_haptics "\"((scene|runtime|net)/|core/(cloth|solids|world|integrate)/|core/collision/collider)")
foreach(dir IN ITEMS server/core/math server/core/geometry server/core/collision
                     server/core/haptics)
  forbid_includes(${dir} "${not_haptics}"
    "felt_haptics includes nothing of the server beyond core/{math,geometry,collision,haptics}"
    "/collider\\.(hpp|cpp)$")
endforeach()
forbid_includes(client_cpp "${not_haptics}"
  "the client includes nothing of the server but felt_haptics")
forbid_includes(common "${server_layers}" "the common libraries include nothing of the server")
