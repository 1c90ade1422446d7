# The strip adjustment's Slurm job arrays on a single-node cluster on localhost (slurm-wlm + munge,
# root): the result equals the single-process run to 1e-9 relative.
add_test(NAME strips_slurm_job_arrays
         COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/slurm_strip_adjust.sh ${PROJECT_BINARY_DIR} ${PROJECT_SOURCE_DIR})
set_tests_properties(strips_slurm_job_arrays PROPERTIES TIMEOUT 900 RUN_SERIAL TRUE)

# The staged run (job arrays as local processes) keeps the single-process verdict and exit status.
add_test(NAME strips_staged_run_keeps_the_verdict
         COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/staged_unreliable.sh ${PROJECT_BINARY_DIR} ${PROJECT_SOURCE_DIR}
                 ${PCL_LS3D_SHARED_DATA_DIR})
set_tests_properties(strips_staged_run_keeps_the_verdict PROPERTIES TIMEOUT 600 SKIP_RETURN_CODE 77)
