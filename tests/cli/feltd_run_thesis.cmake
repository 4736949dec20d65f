# `feltd run` on a scene of the second thesis: exits 0, stays finite and reports the scene's
# size in its stats JSON the way Table 7.2 counts it.
# Inputs: FELTD, SCENE, SCENE_DIR, OUT, STEPS, and the expected NODES EDGES TRIANGLES TETS.
execute_process(COMMAND ${FELTD} run ${SCENE} --scene-dir ${SCENE_DIR} --steps ${STEPS}
                        --stats-json ${OUT}
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "feltd run failed (${result}): ${output}${errors}")
endif()
if(NOT output MATCHES "solids: ${NODES} nodes, ${EDGES} edges, ${TRIANGLES} triangles, ${TETS} tetrahedra")
  message(FATAL_ERROR "feltd run printed no or wrong solid counts: ${output}")
endif()
file(READ ${OUT} stats)
string(JSON nonfinite GET "${stats}" nonfinite)
foreach(key nodes edges triangles tets)
  string(TOUPPER ${key} expected_var)
  string(JSON value GET "${stats}" solids totals ${key})
  if(NOT value EQUAL ${${expected_var}})
    message(FATAL_ERROR "solids.totals.${key} is ${value}, expected ${${expected_var}}")
  endif()
endforeach()
foreach(key mean_colliding_nodes max_colliding_nodes mean_stage_ms max_stage_ms)
  string(JSON value GET "${stats}" solids ${key})
endforeach()
if(NOT nonfinite STREQUAL "OFF")
  message(FATAL_ERROR "non-finite state: ${stats}")
endif()
