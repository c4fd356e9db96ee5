# The GL 4.5 core loader, generated at build time by Debian's glad2. --reproducible
# uses the Khronos XML that ships with the package, so no network is needed and the
# output is the same on every machine. No extensions: everything we use (KHR_debug,
# DSA, clip control) is core in 4.5.
find_program(GLAD_EXECUTABLE glad PATHS /usr/bin NO_DEFAULT_PATH REQUIRED)
set(GLAD_OUT ${CMAKE_BINARY_DIR}/glad)
add_custom_command(
  OUTPUT ${GLAD_OUT}/src/gl.c ${GLAD_OUT}/include/glad/gl.h
  COMMAND ${GLAD_EXECUTABLE} --reproducible --quiet --api gl:core=4.5 --extensions ""
          --out-path ${GLAD_OUT} c
  COMMENT "Generating the GL 4.5 core loader with glad"
  VERBATIM)
add_library(glad STATIC ${GLAD_OUT}/src/gl.c ${GLAD_OUT}/include/glad/gl.h)
target_include_directories(glad SYSTEM PUBLIC ${GLAD_OUT}/include)
set_target_properties(glad PROPERTIES POSITION_INDEPENDENT_CODE ON)
