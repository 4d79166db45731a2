# The `install` test (tests/CMakeLists.txt), run with cmake -P: installs the build into a fresh
# prefix, builds tests/install/consumer against that prefix alone (with the README's library
# example taken from README.md itself, so the two cannot drift), runs the example on EXEMPLAR and
# checks what it wrote. Arguments (-D): SOURCE_DIR, BUILD_DIR, WORK_DIR, GENERATOR, MAKE_PROGRAM,
# CXX_COMPILER, BUILD_TYPE, EXEMPLAR.

function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    string(REPLACE ";" " " command "${ARGV}")
    message(FATAL_ERROR "failed (${status}): ${command}")
  endif()
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# The first ```cpp block after "## Library".
file(READ ${SOURCE_DIR}/README.md readme)
string(FIND "${readme}" "\n## Library\n" section)
if(section EQUAL -1)
  message(FATAL_ERROR "README.md has no '## Library' section")
endif()
string(SUBSTRING "${readme}" ${section} -1 readme)
set(fence "```cpp\n")
string(FIND "${readme}" "${fence}" begin)
if(begin EQUAL -1)
  message(FATAL_ERROR "README.md has no ```cpp block under '## Library'")
endif()
string(LENGTH "${fence}" fence_length)
math(EXPR begin "${begin} + ${fence_length}")
string(SUBSTRING "${readme}" ${begin} -1 readme)
string(FIND "${readme}" "\n```" end)
string(SUBSTRING "${readme}" 0 ${end} example)
file(WRITE ${WORK_DIR}/readme_example.cpp "${example}\n")

run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/install/consumer -B ${WORK_DIR}/build
    -G ${GENERATOR} -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM} -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    -DCMAKE_BUILD_TYPE=${BUILD_TYPE} -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DREADME_EXAMPLE=${WORK_DIR}/readme_example.cpp)
# The package must come from the prefix, not from anywhere else on the machine.
file(STRINGS ${WORK_DIR}/build/CMakeCache.txt package_dir REGEX "^stochtex_DIR:")
if(NOT package_dir MATCHES "=${prefix}/")
  message(FATAL_ERROR "the consumer found stochtex outside ${prefix}: ${package_dir}")
endif()
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)

set(run_dir ${WORK_DIR}/run)
file(MAKE_DIRECTORY ${run_dir})
file(COPY_FILE ${EXEMPLAR} ${run_dir}/exemplar.png)
execute_process(COMMAND ${WORK_DIR}/build/readme_example WORKING_DIRECTORY ${run_dir}
                RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the README example failed (${status})")
endif()
run(${WORK_DIR}/build/check_outputs ${run_dir}/exemplar.png ${run_dir}/exemplar.stx
    ${run_dir}/texture.png)
