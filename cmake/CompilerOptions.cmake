# One place for warnings, applied to every target we build (KISS-ICP style). PCL_LS3D_WERROR
# (on in the test command, scripts/run_tests.sh) makes them errors, except GCC's flow-based
# maybe-uninitialized and array-bounds, which report false positives inside Eigen's fixed-size
# code once it is inlined into ours (docs/DECISIONS.md): they stay warnings.
option(PCL_LS3D_WERROR "Treat compiler warnings in the project's own code as errors" OFF)
function(pcl_ls3d_set_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wno-unused-parameter)
    if(PCL_LS3D_WERROR)
      target_compile_options(${target} PRIVATE -Werror)
      if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
        target_compile_options(${target} PRIVATE -Wno-error=maybe-uninitialized -Wno-error=array-bounds)
      endif()
    endif()
  endif()
endfunction()

# PCL_LS3D_SANITIZE: ASan + UBSan. The flags are PUBLIC on the library, so every target that links
# it (tools, tests, benchmarks, and a consumer of the installed package) is instrumented and
# links the runtimes. Any UB report aborts (no recovery). EIGEN_MALLOC_ALREADY_ALIGNED=1: under
# ASan (__SANITIZE_ADDRESS__) Eigen would switch to its own aligned malloc, and an Eigen object
# allocated in our code but freed inside the uninstrumented system PCL (or the reverse) would be
# reported as a bad free; glibc's malloc is 16-byte aligned on x86-64, so plain malloc is right.
function(pcl_ls3d_set_sanitizers target)
  if(PCL_LS3D_SANITIZE)
    set(flags -fsanitize=address,undefined -fno-sanitize-recover=undefined
              -fno-omit-frame-pointer)
    target_compile_options(${target} PUBLIC ${flags})
    target_link_options(${target} PUBLIC -fsanitize=address,undefined)
    target_compile_definitions(${target} PUBLIC EIGEN_MALLOC_ALREADY_ALIGNED=1)
  endif()
endfunction()
