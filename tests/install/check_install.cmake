# Installs the build into a fresh prefix; configures, builds and runs tests/install/consumer
# and examples/ against it (find_package(streak), streak::streak); the consumer's render must
# equal the installed CLI's to the bit. Arguments: BUILD_DIR, SOURCE_DIR, WORK.
function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK})
set(prefix ${WORK}/prefix)
run("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(file include/streak/streak.h include/streak/error.h lib/cmake/streak/streakConfig.cmake
             lib/cmake/streak/streakConfigVersion.cmake bin/streak)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "the install lacks ${file}")
  endif()
endforeach()

foreach(project consumer examples)
  if(project STREQUAL "consumer")
    set(source ${SOURCE_DIR}/tests/install/consumer)
  else()
    set(source ${SOURCE_DIR}/examples)
  endif()
  run("configuring ${project}" ${CMAKE_COMMAND} -S ${source} -B ${WORK}/${project} -G Ninja -DCMAKE_BUILD_TYPE=Release
      -DCMAKE_PREFIX_PATH=${prefix})
  run("building ${project}" ${CMAKE_COMMAND} --build ${WORK}/${project})
endforeach()

set(scene "builtin:cubes?n=50")
run("the consumer" ${WORK}/consumer/consumer ${scene} ${WORK}/api.exr)
run("the CLI" ${prefix}/bin/streak render ${scene} -m analytic --width 64 --height 48 -o ${WORK}/cli.exr)
run("compare" ${prefix}/bin/streak compare ${WORK}/api.exr ${WORK}/cli.exr)
if(NOT last_output MATCHES "PSNR: inf dB")
  message(FATAL_ERROR "the consumer's image differs from the CLI's:\n${last_output}")
endif()
run("the example" ${WORK}/examples/moving_mesh ${WORK}/example)
if(NOT EXISTS ${WORK}/example-analytic.png OR NOT EXISTS ${WORK}/example-accumulation.png)
  message(FATAL_ERROR "the example wrote no images: ${last_output}")
endif()
message(STATUS "consumer = CLI to the bit; example: ${last_output}")
