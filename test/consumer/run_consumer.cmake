# Stages an install of the build tree, then configures, builds and runs test/consumer against it,
# and runs an installed tool from the staged prefix (its install RPATH must find the library).
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_consumer.cmake needs -D${var}=...")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK_DIR})
set(stage ${WORK_DIR}/stage)
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${stage}
                RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "staged install failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build
                        -DCMAKE_PREFIX_PATH=${stage} -DCMAKE_BUILD_TYPE=Release
                RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "configuring the consumer against the staged install failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "building the consumer failed (${rc})")
endif()
execute_process(COMMAND ${WORK_DIR}/build/consumer RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "the consumer ran but failed (${rc})")
endif()

# The installed tool, with no LD_LIBRARY_PATH and no build tree on its RPATH, reads a file.
unset(ENV{LD_LIBRARY_PATH})
set(tool ${stage}/bin/pcl_ls3d_info)
if(NOT EXISTS ${tool})
  message(FATAL_ERROR "the staged install has no ${tool}")
endif()
file(WRITE ${WORK_DIR}/three.xyz "1 2 3\n4 5 6\n7 8 9\n")
execute_process(COMMAND ${tool} ${WORK_DIR}/three.xyz RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(rc OR NOT out MATCHES "points in file 3, loaded 3")
  message(FATAL_ERROR "the installed pcl_ls3d_info did not run (${rc}): ${out} ${err}")
endif()
message(STATUS "installed tool ran: ${out}")
