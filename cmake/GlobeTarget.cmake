# globe_target(NAME): the one place that sets language standard, warnings and
# sanitizers for every target of the project.
function(globe_target name)
  target_compile_features(${name} PUBLIC cxx_std_20)
  set_target_properties(${name} PROPERTIES CXX_EXTENSIONS OFF)
  target_compile_options(${name} PRIVATE -Wall -Wextra -Wpedantic)
  # GCC 12 at -O3 reports impossible overlaps inside libstdc++'s string code
  # (GCC bug 105651), a false positive that -Werror would turn into a failure.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${name} PRIVATE -Wno-restrict)
  endif()
  if(GLOBE_WERROR)
    target_compile_options(${name} PRIVATE -Werror)
  endif()
  if(GLOBE_SANITIZE)
    target_compile_options(${name} PRIVATE -fsanitize=${GLOBE_SANITIZE} -fno-omit-frame-pointer
                                           -fno-sanitize-recover=all)
    target_link_options(${name} PRIVATE -fsanitize=${GLOBE_SANITIZE})
    # One name for "under ASan" with either compiler (GCC defines
    # __SANITIZE_ADDRESS__, clang 14 only answers __has_feature).
    if(GLOBE_SANITIZE MATCHES "address")
      target_compile_definitions(${name} PRIVATE GLOBE_ADDRESS_SANITIZER=1)
    endif()
  endif()
  if(GLOBE_FUZZ)  # coverage feedback for libFuzzer in every library it links
    target_compile_options(${name} PRIVATE -fsanitize=fuzzer-no-link)
  endif()
endfunction()
