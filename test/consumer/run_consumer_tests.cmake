# cmake -P script run by the ctest `consumer_packages` (see CMakeLists.txt here).
# Inputs (-D): TOP_BUILD_DIR, INSTALL_FROM_DIR, PROJECT_DIR, WORK_DIR, CONFIG,
# GENERATOR, MAKE_PROGRAM, CXX_COMPILER.
cmake_minimum_required(VERSION 3.16)

foreach(var TOP_BUILD_DIR INSTALL_FROM_DIR PROJECT_DIR WORK_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "run_consumer_tests.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT CONFIG)
  set(CONFIG Release)
endif()
cmake_host_system_information(RESULT JOBS QUERY NUMBER_OF_LOGICAL_CORES)
if(NOT JOBS OR JOBS LESS 1)
  set(JOBS 2)
endif()

set(PREFIX ${WORK_DIR}/prefix)
set(CONSUMER_BUILD ${WORK_DIR}/build)

# Runs a command, streaming its output; stops the test if it fails.
function(run_step what)
  message(STATUS "consumer test: ${what}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "consumer test: ${what} FAILED (exit ${rc})")
  endif()
endfunction()

set(generator_args)
if(GENERATOR)
  list(APPEND generator_args -G ${GENERATOR})
endif()
if(MAKE_PROGRAM)
  list(APPEND generator_args -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM})
endif()
if(CXX_COMPILER)
  list(APPEND generator_args -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
endif()

# 1. The library is built (no-op after a full build) and installed into a fresh
#    private prefix. file(INSTALL) keeps timestamps, so the consumer build below
#    stays incremental across runs.
run_step("build fcl_disk in ${TOP_BUILD_DIR}"
  ${CMAKE_COMMAND} --build ${TOP_BUILD_DIR} --target fcl_disk --config ${CONFIG} --parallel ${JOBS})
file(REMOVE_RECURSE ${PREFIX})
run_step("install into ${PREFIX}"
  ${CMAKE_COMMAND} --install ${INSTALL_FROM_DIR} --prefix ${PREFIX} --config ${CONFIG})
file(GLOB_RECURSE config_files ${PREFIX}/*/fcl_diskConfig.cmake)
file(GLOB_RECURSE version_files ${PREFIX}/*/fcl_diskConfigVersion.cmake)
if(NOT config_files OR NOT version_files OR NOT EXISTS ${PREFIX}/include/fcl_disk/fcl_disk.h)
  message(FATAL_ERROR "consumer test: the install tree lacks fcl_diskConfig.cmake, "
                      "fcl_diskConfigVersion.cmake or include/fcl_disk/fcl_disk.h")
endif()

# 2. The version file rejects incompatible requests (SameMinorVersion): configuring
#    the consumer with find_package(fcl_disk <v> CONFIG REQUIRED) must fail.
foreach(bad_version 0.2 1.0)
  set(dir ${WORK_DIR}/version_${bad_version})
  file(REMOVE_RECURSE ${dir})
  execute_process(
    COMMAND ${CMAKE_COMMAND} -S ${PROJECT_DIR} -B ${dir} ${generator_args}
      -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON
      -DCONSUMER_FCL_DISK_VERSION=${bad_version}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0)
    message(FATAL_ERROR "consumer test: find_package(fcl_disk ${bad_version} CONFIG REQUIRED) "
                        "accepted the installed fcl_disk; the version file does not work:\n${out}${err}")
  endif()
  if(NOT err MATCHES "fcl_disk" OR NOT err MATCHES "[Vv]ersion")
    message(FATAL_ERROR "consumer test: find_package(fcl_disk ${bad_version}) failed, but not "
                        "because of the version:\n${out}${err}")
  endif()
  message(STATUS "consumer test: find_package(fcl_disk ${bad_version} CONFIG REQUIRED) rejected, as it must")
  file(REMOVE_RECURSE ${dir})
endforeach()

# 3. Configure and build the consumer against the install tree only.
run_step("configure the consumer project with find_package(fcl_disk 0.1 CONFIG REQUIRED)"
  ${CMAKE_COMMAND} -S ${PROJECT_DIR} -B ${CONSUMER_BUILD} ${generator_args}
    -DCMAKE_BUILD_TYPE=${CONFIG}
    -DCMAKE_PREFIX_PATH=${PREFIX}
    -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON
    -DCONSUMER_FCL_DISK_VERSION=0.1
    -DFCL_DISK_EXPECTED_PREFIX=${PREFIX})
# FCL's headers make the compiler verbose; the build log goes to a file, and its
# tail is shown if the build fails.
message(STATUS "consumer test: build the consumer project (log: ${WORK_DIR}/build.log)")
execute_process(
  COMMAND ${CMAKE_COMMAND} --build ${CONSUMER_BUILD} --config ${CONFIG} --parallel ${JOBS}
  RESULT_VARIABLE rc OUTPUT_FILE ${WORK_DIR}/build.log ERROR_FILE ${WORK_DIR}/build.log)
if(NOT rc EQUAL 0)
  execute_process(COMMAND tail -n 150 ${WORK_DIR}/build.log)
  message(FATAL_ERROR "consumer test: building the consumer project FAILED (exit ${rc}); "
                      "full log: ${WORK_DIR}/build.log")
endif()

# 4. Run every way of linking and loading; report all, then fail if any failed.
#    LD_LIBRARY_PATH/LD_PRELOAD are cleared so that only the binaries' RUNPATHs
#    decide which libfcl_disk is loaded (the programs check it is the installed one).
#    Each run is "program[:argument]".
set(runs
  "consumer_disk_first"
  "consumer_fcl_first"
  "consumer_dlopen_host:local"
  "consumer_dlopen_host:global"
  "consumer_dlopen_host_exports:local")
set(failed)
foreach(spec IN LISTS runs)
  string(REPLACE ":" ";" run "${spec}")
  list(GET run 0 exe)
  set(args ${run})
  list(REMOVE_AT args 0)
  set(path ${CONSUMER_BUILD}/${exe})
  if(NOT EXISTS ${path})
    set(path ${CONSUMER_BUILD}/${CONFIG}/${exe})
  endif()
  string(REPLACE ";" " " shown "${run}")
  string(REPLACE ";" "_" log_name "${run}")
  set(log ${WORK_DIR}/${log_name}.log)
  message(STATUS "consumer test: running ${shown} (full log: ${log})")
  execute_process(
    COMMAND ${CMAKE_COMMAND} -E env --unset=LD_LIBRARY_PATH --unset=LD_PRELOAD ${path} ${args}
    RESULT_VARIABLE rc OUTPUT_FILE ${log} ERROR_FILE ${log})
  # One line per check is in the log; show the failures, the bindings and summaries.
  file(STRINGS ${log} passed REGEX "^\\[PASS\\]")
  list(LENGTH passed n_passed)
  file(STRINGS ${log} shown_lines REGEX "^(\\[FAIL\\]|\\[info\\]|====|consumer_|planner_plugin|usage)")
  foreach(line IN LISTS shown_lines)
    message("  ${line}")
  endforeach()
  if(rc EQUAL 0)
    message(STATUS "consumer test: ${shown}: passed (${n_passed} checks)")
  else()
    message("  ... last lines of ${log}:")
    execute_process(COMMAND tail -n 5 ${log})
    message(STATUS "consumer test: ${shown}: FAILED (exit ${rc}, ${n_passed} checks passed)")
    list(APPEND failed "${shown} (exit ${rc})")
  endif()
endforeach()
if(failed)
  string(REPLACE ";" ", " failed "${failed}")
  message(FATAL_ERROR "consumer test: failed: ${failed}")
endif()
message(STATUS "consumer test: all consumer programs passed")
