# Configures and builds the sanitizer build (tests/sanitize/CMakeLists.txt) in BUILD, against the
# main build PREBUILT; the main build's test SanitizerBuild runs it:
#
#   cmake -DSOURCE=. -DBUILD=build/sanitize -DPREBUILT=build -DCXX=clang++-14 -DGENERATOR=Ninja \
#         [-DLAUNCHER=ccache] -P tests/sanitize/build.cmake
foreach(var SOURCE BUILD PREBUILT CXX GENERATOR)
  if(NOT ${var})
    message(FATAL_ERROR "tests/sanitize/build.cmake: -D${var}=... is missing")
  endif()
endforeach()
set(launcher "")
if(LAUNCHER)
  set(launcher "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}")
endif()
# Warnings are the main build's business (GCC, -Werror); clang's own ones only print here.
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE} -B ${BUILD} -G ${GENERATOR} -DHYBRIDLAB_SANITIZE=ON
                        -DHYBRIDLAB_PREBUILT=${PREBUILT} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=Release
                        -DHYBRIDLAB_WERROR=OFF ${launcher}
                COMMAND_ERROR_IS_FATAL ANY)
cmake_host_system_information(RESULT cores QUERY NUMBER_OF_LOGICAL_CORES)
string(TIMESTAMP start "%s")
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD} -j ${cores} COMMAND_ERROR_IS_FATAL ANY)
string(TIMESTAMP end "%s")
math(EXPR seconds "${end} - ${start}")
message(STATUS "sanitizer build: ${seconds} s on ${cores} cores")
