# GMP for a consumer of the static libbatchccd.a. The build found GMP with
# pkg-config as the imported target PkgConfig::GMP, and the exported target
# names it, so recreate that target: through pkg-config when it is there,
# else from gmp.h and the library found directly.
if(TARGET PkgConfig::GMP)
  return()
endif()
find_package(PkgConfig QUIET)
if(PKG_CONFIG_FOUND)
  pkg_check_modules(GMP QUIET IMPORTED_TARGET gmp)
endif()
if(NOT TARGET PkgConfig::GMP)
  find_path(BATCHCCD_GMP_INCLUDE_DIR gmp.h)
  find_library(BATCHCCD_GMP_LIBRARY gmp)
  if(BATCHCCD_GMP_INCLUDE_DIR AND BATCHCCD_GMP_LIBRARY)
    add_library(PkgConfig::GMP INTERFACE IMPORTED)
    set_target_properties(PkgConfig::GMP PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES ${BATCHCCD_GMP_INCLUDE_DIR}
      INTERFACE_LINK_LIBRARIES ${BATCHCCD_GMP_LIBRARY})
  endif()
endif()
