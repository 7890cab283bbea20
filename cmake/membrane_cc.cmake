# How every library, program and test here is declared: membrane_cc_library,
# membrane_cc_binary and membrane_cc_test (on the model of Abseil's absl_cc_library). Each
# target names its own sources, headers and dependencies, and is compiled with the project's
# one warning set, MEMBRANE_DEFAULT_COPTS. Include paths are from the repository root
# ("core/engine/voxel_grid.h"), for every target alike.

# Off for users: a newer compiler may warn about code that this one passes, and a build must
# not fail on that. CI (deploy/run-tests.sh) turns it on, so no warning lands unseen.
option(MEMBRANE_WERROR "Treat compiler warnings as errors" OFF)

# Abseil's ABSL_GCC_FLAGS and ABSL_LLVM_FLAGS, the subset both compilers know by these names
# plus each one's own spelling of "a function defined without a declaration in a header"
# (such a function belongs in an anonymous namespace or needs its declaration).
set(MEMBRANE_COMMON_COPTS
  -Wall
  -Wextra
  -Wcast-qual
  -Wformat-security
  -Wnon-virtual-dtor
  -Woverlength-strings
  -Wpointer-arith
  -Wundef
  -Wunused-local-typedefs
  -Wunused-result
  -Wvarargs
  -Wvla
  -Wwrite-strings)
if(CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  set(MEMBRANE_DEFAULT_COPTS ${MEMBRANE_COMMON_COPTS} -Wmissing-prototypes)
else()
  set(MEMBRANE_DEFAULT_COPTS ${MEMBRANE_COMMON_COPTS} -Wconversion-null -Wmissing-declarations)
endif()
if(MEMBRANE_WERROR)
  list(APPEND MEMBRANE_DEFAULT_COPTS -Werror)
endif()

# membrane_cc_library(NAME name [BATCHED] [SRCS file.cc...] [HDRS file.h...]
#                     [DEPS target...] [DEFINES NAME=value...])
# A static library of SRCS, or a header-only (INTERFACE) one when there are none. DEPS are
# public: whoever links `name` links them too, as its headers include theirs. DEFINES are
# private to SRCS. BATCHED compiles SRCS in batches as the tests are (below): for the
# libraries whose every file parses gRPC's or CLI11's headers.
function(membrane_cc_library)
  cmake_parse_arguments(CC "BATCHED" "NAME" "SRCS;HDRS;DEPS;DEFINES" ${ARGN})
  _membrane_cc_check_arguments(membrane_cc_library)
  if(CC_SRCS)
    add_library(${CC_NAME} STATIC ${CC_SRCS} ${CC_HDRS})
    if(CC_BATCHED)
      _membrane_cc_batch(${CC_NAME})
    endif()
    target_compile_options(${CC_NAME} PRIVATE ${MEMBRANE_DEFAULT_COPTS})
    target_compile_definitions(${CC_NAME} PRIVATE ${CC_DEFINES})
    target_include_directories(${CC_NAME} PUBLIC ${PROJECT_SOURCE_DIR})
    target_link_libraries(${CC_NAME} PUBLIC ${CC_DEPS})
  else()
    if(CC_DEFINES)
      message(FATAL_ERROR "membrane_cc_library(${CC_NAME}): DEFINES need SRCS to apply to")
    endif()
    add_library(${CC_NAME} INTERFACE ${CC_HDRS})
    target_include_directories(${CC_NAME} INTERFACE ${PROJECT_SOURCE_DIR})
    target_link_libraries(${CC_NAME} INTERFACE ${CC_DEPS})
  endif()
endfunction()

# membrane_cc_binary(NAME name SRCS file.cc... [DEPS target...] [DEFINES NAME=value...])
# A program of SRCS (one of them holds main) linked with DEPS.
function(membrane_cc_binary)
  cmake_parse_arguments(CC "" "NAME" "SRCS;DEPS;DEFINES" ${ARGN})
  _membrane_cc_check_arguments(membrane_cc_binary)
  add_executable(${CC_NAME} ${CC_SRCS})
  target_compile_options(${CC_NAME} PRIVATE ${MEMBRANE_DEFAULT_COPTS})
  target_compile_definitions(${CC_NAME} PRIVATE ${CC_DEFINES})
  target_include_directories(${CC_NAME} PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(${CC_NAME} PRIVATE ${CC_DEPS})
endfunction()

# Test sources, and the sources of the BATCHED libraries, are compiled in batches (one
# translation unit per 8 files): each file spends most of its 4-5 s parsing the same gtest and
# Abseil headers (gRPC's and CLI11's in the client and the server, up to 17 s a file), and on
# the 2-core CI machine a test folder of 12 files then builds in 15 s of CPU instead of 48
# (tests/io, measured). A file with compile definitions of its own (the version's) stays out
# of the batches, so that a new version still recompiles one file. The container image's
# build, which reads the Release build's objects through ccache, finds the batches too: their
# files name the sources by absolute path, and ccache matches them on the preprocessed text.
# MEMBRANE_UNITY=OFF compiles them one by one, which shows a file missing an include.
option(MEMBRANE_UNITY "compile test binaries and BATCHED libraries in batches" ON)

# membrane_cc_test(NAME name SRCS file_test.cc... [DEPS target...] [DEFINES NAME=value...])
# A GoogleTest binary of SRCS, linked with DEPS, gtest_main and gmock, whose tests ctest runs
# one by one. Tests find ../shared through MEMBRANE_SHARED_DIR. A helper that more than one
# binary uses is a library (tests/support) that each lists in DEPS, never a source compiled
# into each.
function(membrane_cc_test)
  cmake_parse_arguments(CC "" "NAME" "SRCS;DEPS;DEFINES" ${ARGN})
  _membrane_cc_check_arguments(membrane_cc_test)
  add_executable(${CC_NAME} ${CC_SRCS})
  _membrane_cc_batch(${CC_NAME})
  target_compile_options(${CC_NAME} PRIVATE ${MEMBRANE_DEFAULT_COPTS})
  target_compile_definitions(${CC_NAME} PRIVATE ${CC_DEFINES})
  target_include_directories(${CC_NAME} PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(${CC_NAME} PRIVATE ${CC_DEPS} GTest::gtest_main GTest::gmock)
  gtest_discover_tests(${CC_NAME} DISCOVERY_TIMEOUT 60
    PROPERTIES ENVIRONMENT "MEMBRANE_SHARED_DIR=${PROJECT_SOURCE_DIR}/../shared")
endfunction()

# Compiles `target`'s sources 8 to a translation unit when MEMBRANE_UNITY is on.
function(_membrane_cc_batch target)
  if(MEMBRANE_UNITY)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  endif()
endfunction()

# Refuses a call without NAME or with words outside the keywords (a misspelt SRCS would
# otherwise drop its files without a word).
macro(_membrane_cc_check_arguments function)
  if(NOT CC_NAME)
    message(FATAL_ERROR "${function}: NAME is required")
  endif()
  if(CC_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "${function}(${CC_NAME}): unexpected arguments ${CC_UNPARSED_ARGUMENTS}")
  endif()
endmacro()
