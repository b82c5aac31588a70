# SPDX-License-Identifier: BSD-3-Clause
# Helpers shared by every module: one namespaced library target per module, its unit tests,
# warnings, sanitizers, and the install/export set that backs find_package(dynobj).
include(CMakePackageConfigHelpers)

set(DYNOBJ_EXPORT_SET dynobjTargets)

function(dynobj_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                           -Wold-style-cast -Wcast-align -Woverloaded-virtual
                                           -Wformat=2)
  if(DYNOBJ_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(DYNOBJ_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=undefined)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
  if(DYNOBJ_SANITIZE_THREAD)
    target_compile_options(${target} PRIVATE -fsanitize=thread -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=thread)
  endif()
endfunction()

# dynobj_add_module(NAME <m> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# Creates target dynobj_<m> with alias dynobj::<m>; headers in include/dynobj/<m>/.
function(dynobj_add_module)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  set(tgt dynobj_${ARG_NAME})
  add_library(${tgt} ${ARG_SOURCES})
  add_library(dynobj::${ARG_NAME} ALIAS ${tgt})
  set_target_properties(${tgt} PROPERTIES EXPORT_NAME ${ARG_NAME} OUTPUT_NAME dynobj-${ARG_NAME}
                                          VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}
                                          INSTALL_RPATH "$ORIGIN")  # installed modules find each other
  target_compile_features(${tgt} PUBLIC cxx_std_17)
  target_include_directories(${tgt} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
                                           $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${tgt} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  dynobj_set_warnings(${tgt})
  install(TARGETS ${tgt} EXPORT ${DYNOBJ_EXPORT_SET}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(DIRECTORY include/dynobj DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

# dynobj_add_unittests(MODULE <m> SOURCES ... [DEPS ...]): one gtest binary per module.
function(dynobj_add_unittests)
  cmake_parse_arguments(ARG "" "MODULE" "SOURCES;DEPS" ${ARGN})
  if(NOT DYNOBJ_BUILD_TESTS)
    return()
  endif()
  set(tgt dynobj_${ARG_MODULE}_unittests)
  add_executable(${tgt} ${ARG_SOURCES})
  target_link_libraries(${tgt} PRIVATE dynobj::${ARG_MODULE} ${ARG_DEPS} dynobj_test_main)
  target_compile_definitions(${tgt} PRIVATE DYNOBJ_SHARE_DIR="${DYNOBJ_SHARE_DIR_BUILD}"
                                            DYNOBJ_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  dynobj_set_warnings(${tgt})
  gtest_discover_tests(${tgt} DISCOVERY_MODE PRE_TEST TEST_PREFIX "${ARG_MODULE}." PROPERTIES LABELS unit)
endfunction()

# dynobj_add_app(NAME <app> SOURCES ... DEPS ...): a thin command-line front end.
function(dynobj_add_app)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;DEPS" ${ARGN})
  add_executable(${ARG_NAME} ${ARG_SOURCES})
  target_link_libraries(${ARG_NAME} PRIVATE ${ARG_DEPS} dynobj::io)  # io: the crash guard (AppMain.h)
  # Shipped data: the source tree's share/dynobj when run from a build, else the installed copy.
  target_compile_definitions(${ARG_NAME} PRIVATE
    DYNOBJ_SHARE_DIR_BUILD="${DYNOBJ_SHARE_DIR_BUILD}"
    DYNOBJ_SHARE_DIR_INSTALLED="${CMAKE_INSTALL_PREFIX}/${DYNOBJ_SHARE_DIR_INSTALL}")
  dynobj_set_warnings(${ARG_NAME})
  install(TARGETS ${ARG_NAME} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()

function(dynobj_install_package_config)
  set(cfgdir ${CMAKE_INSTALL_LIBDIR}/cmake/dynobj)
  install(EXPORT ${DYNOBJ_EXPORT_SET} NAMESPACE dynobj:: DESTINATION ${cfgdir} FILE dynobjTargets.cmake)
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/dynobjConfig.cmake.in
                                ${PROJECT_BINARY_DIR}/dynobjConfig.cmake INSTALL_DESTINATION ${cfgdir}
                                PATH_VARS DYNOBJ_SHARE_DIR_INSTALL)
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/dynobjConfigVersion.cmake
                                   COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/dynobjConfig.cmake ${PROJECT_BINARY_DIR}/dynobjConfigVersion.cmake
          DESTINATION ${cfgdir})
endfunction()
