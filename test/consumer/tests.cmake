# find_package(pcl_ls3d) from a separate project against a staged install of this build.
add_test(NAME consumer_find_package
         COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR}
                 -DSOURCE_DIR=${CMAKE_CURRENT_LIST_DIR}
                 -DWORK_DIR=${PROJECT_BINARY_DIR}/consumer_test
                 -P ${CMAKE_CURRENT_LIST_DIR}/run_consumer.cmake)
set_tests_properties(consumer_find_package PROPERTIES TIMEOUT 600 RUN_SERIAL TRUE)
