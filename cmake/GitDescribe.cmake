# GAITOPT_GIT_DESCRIBE: `git describe --always --dirty` of the source tree, or the project
# version outside a git checkout (e.g. a release tarball). Configure is re-run on every commit
# or checkout (the HEAD reflog changes), so --version follows the commit; `-dirty` reflects the
# work tree at the last configure.
set(GAITOPT_GIT_DESCRIBE "${PROJECT_VERSION}")
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} describe --always --dirty
                  WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                  OUTPUT_VARIABLE git_describe RESULT_VARIABLE git_result
                  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --absolute-git-dir
                  WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                  OUTPUT_VARIABLE git_dir OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(git_result EQUAL 0 AND git_describe)
    set(GAITOPT_GIT_DESCRIBE "${git_describe}")
    if(EXISTS "${git_dir}/logs/HEAD")
      set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${git_dir}/logs/HEAD")
    endif()
  endif()
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/gaitopt_version.hpp.in
               ${PROJECT_BINARY_DIR}/generated/gaitopt_version.hpp @ONLY)
