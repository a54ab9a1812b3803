# `cpack -G DEB` from a build: a .deb with the programs, their modules, the libraries, the headers
# and the CMake package. dpkg-shlibdeps finds the run-time libraries the programs and modules link;
# EGL and GL, which rendering opens itself, are named; the -dev packages are those the CMake
# package's find_dependency calls need.
set(CPACK_PACKAGE_NAME tinlod)
set(CPACK_PACKAGE_VENDOR tinlod)
set(CPACK_PACKAGE_CONTACT "tinlod maintainers <tinlod@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "View-dependent TINs from DEMs and meshes (library, CLI, viewer)")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libegl1, libopengl0, libopenmesh-dev, libglm-dev, \
nlohmann-json3-dev, libopenimageio-dev, libtiff-dev, libpng-dev, libproj-dev")
include(CPack)
