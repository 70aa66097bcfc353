# Installs ptlab into a fresh prefix, builds examples/chi2_external against it (find_package and
# pkg-config) and runs it. cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -P this file.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run what)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc
    OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc})")
  endif()
endfunction()

run("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
# The public header must not pull in Highway or the engine.
file(READ ${prefix}/include/ptlab/chi2.h header)
if(header MATCHES "hwy/|engine/")
  message(FATAL_ERROR "the installed ptlab/chi2.h includes Highway or engine headers")
endif()
run("configure the example" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/chi2_external
  -B ${WORK_DIR}/build -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run("build the example" ${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run("run the example" ${WORK_DIR}/build/power_cosine_check)
# pkg-config: the same program compiles and links from the .pc file alone.
set(ENV{PKG_CONFIG_PATH} ${prefix}/lib/pkgconfig)
execute_process(COMMAND pkg-config --cflags --libs ptlab-chi2 OUTPUT_VARIABLE flags
  RESULT_VARIABLE rc OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pkg-config does not find ptlab-chi2")
endif()
separate_arguments(flags UNIX_COMMAND "${flags}")
run("compile with pkg-config" c++ -O1 ${SOURCE_DIR}/examples/chi2_external/power_cosine_check.cpp
  ${flags} -o ${WORK_DIR}/power_cosine_check_pc)
