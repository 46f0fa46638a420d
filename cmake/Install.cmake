# `cmake --install build --prefix P` and `cpack -G DEB` (docs/install.md):
# the programs, the tile-format library with its headers, and the docs.
include(GNUInstallDirs)
set(GLOBE_DOCDIR ${CMAKE_INSTALL_DATAROOTDIR}/doc/globe-tiles)

# globe-tiler execs globe-tiler-gdal from its own folder: both go to bin.
install(TARGETS globe-tiler globe-tiler-gdal globe-vectorize globe-view globe-serve
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS tileformat ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
# GDAL looks for plugins in LIBDIR/gdalplugins of its own prefix (Debian:
# /usr/lib/x86_64-linux-gnu/gdalplugins, where the .deb puts it); elsewhere
# point GDAL_DRIVER_PATH at this folder (docs/gdal.md).
get_target_property(GLOBE_GDAL_LIBRARY GDAL::GDAL LOCATION)
get_filename_component(GLOBE_GDAL_LIBDIR "${GLOBE_GDAL_LIBRARY}" DIRECTORY)
file(RELATIVE_PATH GLOBE_GDAL_PLUGINS /usr "${GLOBE_GDAL_LIBDIR}/gdalplugins")
if(GLOBE_GDAL_PLUGINS MATCHES "^\\.\\.")  # GDAL is not under /usr
  set(GLOBE_GDAL_PLUGINS ${CMAKE_INSTALL_LIBDIR}/gdalplugins)
endif()
install(TARGETS gdal_GlobeTiles LIBRARY DESTINATION ${GLOBE_GDAL_PLUGINS})
install(DIRECTORY lib/tileformat/include/tileformat DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES README.md LICENSE DESTINATION ${GLOBE_DOCDIR})
install(DIRECTORY docs/ DESTINATION ${GLOBE_DOCDIR} FILES_MATCHING PATTERN "*.md")

set(CPACK_PACKAGE_NAME "globe-tiles")
set(CPACK_PACKAGE_VENDOR "GlobeEngine tiles")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Terrain, imagery, line and point packages for 3D geographic viewing, and their viewer")
set(CPACK_PACKAGE_CONTACT "GlobeEngine tiles maintainers <globe-tiles@localhost>")
set(CPACK_RESOURCE_FILE_LICENSE "${PROJECT_SOURCE_DIR}/LICENSE")
set(CPACK_STRIP_FILES ON)
set(CPACK_PACKAGING_INSTALL_PREFIX "/usr")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION "science")
# The Debian libraries the programs link (GDAL, PROJ, SQLite, zstd, Mesa...),
# found by dpkg-shlibdeps from the binaries themselves.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
include(CPack)
