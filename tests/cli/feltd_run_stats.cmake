# `feltd run` on the default scene with an override: exits 0 and writes the stats JSON with the
# fields the README promises and the counts of a 20 x 20 grid cloth.
execute_process(COMMAND ${FELTD} run ${SCENE} --steps 200 --set bodies.0.integrator=explicit_euler
                        --set time_step=0.0005 --stats-json ${OUT}
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "feltd run failed (${result}): ${output}${errors}")
endif()
file(READ ${OUT} stats)
string(JSON steps GET "${stats}" steps)
string(JSON sim_time GET "${stats}" sim_time)
string(JSON nonfinite GET "${stats}" nonfinite)
string(JSON particles GET "${stats}" bodies 0 particles)
string(JSON edges GET "${stats}" bodies 0 edges)
string(JSON triangles GET "${stats}" bodies 0 triangles)
string(JSON name GET "${stats}" bodies 0 name)
foreach(key wall_seconds ms_per_step)
  string(JSON value GET "${stats}" ${key})
endforeach()
foreach(key tets kinetic_energy max_strain)
  string(JSON value GET "${stats}" bodies 0 ${key})
endforeach()
# 20 x 20 grid: 400 particles, 2*19*19 = 722 triangles, 19*20*2 + 19*19 = 1121 edges
if(NOT steps EQUAL 200 OR NOT particles EQUAL 400 OR NOT triangles EQUAL 722 OR NOT edges EQUAL 1121
   OR NOT name STREQUAL "curtain" OR NOT nonfinite STREQUAL "OFF")
  message(FATAL_ERROR "unexpected stats: ${stats}")
endif()
# 200 steps of the overridden 0.5 ms step
if(NOT sim_time MATCHES "^0\\.1(0*|0*1)?$" AND NOT sim_time MATCHES "^0\\.09999")
  message(FATAL_ERROR "sim_time ${sim_time} is not 200 x 0.5 ms")
endif()
# the cloth's per-step profile: every stage of the cloth step, in milliseconds
foreach(stage integration stretch_limit colliders self_collision constraints health)
  string(JSON ms GET "${stats}" cloth mean_stage_ms ${stage})
  string(JSON ms GET "${stats}" cloth max_stage_ms ${stage})
endforeach()
string(JSON integration GET "${stats}" cloth mean_stage_ms integration)
if(NOT integration GREATER 0)
  message(FATAL_ERROR "the cloth's integration took no time: ${stats}")
endif()
