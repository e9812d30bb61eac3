# Install rules: headers, the library, a relocatable CMake package
# (find_package(batchccd CONFIG) -> batchccd::batchccd) and a pkg-config file.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(BATCHCCD_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/batchccd)
set(BATCHCCD_PKGCONFIG_DIR ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

install(TARGETS batchccd EXPORT batchccdTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/lib/include/batchccd
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.hpp")
get_target_property(batchccd_binary_dir batchccd BINARY_DIR)  # version.hpp is generated there
install(FILES ${batchccd_binary_dir}/include/batchccd/version.hpp
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/batchccd)
if(TARGET batchccd_cli AND BATCHCCD_BUILD_CLI)
  install(TARGETS batchccd_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

# A static archive leaves its references to TBB and GMP for the consumer's
# link line (the export names them as $<LINK_ONLY:...>), so the package must
# find them; a shared library resolves them itself.
get_target_property(batchccd_type batchccd TYPE)
if(batchccd_type STREQUAL "STATIC_LIBRARY")
  set(BATCHCCD_STATIC ON)
  set(BATCHCCD_PC_REQUIRES "eigen3 tbb gmp")
  set(BATCHCCD_PC_REQUIRES_PRIVATE "")
else()
  set(BATCHCCD_STATIC OFF)
  set(BATCHCCD_PC_REQUIRES "eigen3")
  set(BATCHCCD_PC_REQUIRES_PRIVATE "tbb gmp")
endif()

install(EXPORT batchccdTargets NAMESPACE batchccd:: DESTINATION ${BATCHCCD_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/batchccdConfig.cmake.in
  ${PROJECT_BINARY_DIR}/batchccdConfig.cmake INSTALL_DESTINATION ${BATCHCCD_CMAKE_DIR})
# 0.x: a minor release may break the API, so only the same MAJOR.MINOR matches.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/batchccdConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES
  ${PROJECT_BINARY_DIR}/batchccdConfig.cmake
  ${PROJECT_BINARY_DIR}/batchccdConfigVersion.cmake
  ${CMAKE_CURRENT_LIST_DIR}/batchccdFindGMP.cmake
  DESTINATION ${BATCHCCD_CMAKE_DIR})

# pkg-config: prefix relative to the .pc file, so the tree can be moved and
# `cmake --install --prefix` anywhere works.
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  message(FATAL_ERROR "batchccd: the pkg-config file needs a relative CMAKE_INSTALL_LIBDIR")
endif()
file(RELATIVE_PATH BATCHCCD_PC_TO_PREFIX /prefix/${BATCHCCD_PKGCONFIG_DIR} /prefix)
string(REGEX REPLACE "/$" "" BATCHCCD_PC_TO_PREFIX "${BATCHCCD_PC_TO_PREFIX}")
configure_file(${CMAKE_CURRENT_LIST_DIR}/batchccd.pc.in ${PROJECT_BINARY_DIR}/batchccd.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/batchccd.pc DESTINATION ${BATCHCCD_PKGCONFIG_DIR})
