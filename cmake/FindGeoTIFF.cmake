# Finds libgeotiff (Debian's libgeotiff-dev ships no CMake config). Defines GeoTIFF::GeoTIFF.
find_path(GeoTIFF_INCLUDE_DIR geotiff.h PATH_SUFFIXES geotiff libgeotiff)
find_library(GeoTIFF_LIBRARY NAMES geotiff)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(GeoTIFF REQUIRED_VARS GeoTIFF_LIBRARY GeoTIFF_INCLUDE_DIR)
if(GeoTIFF_FOUND AND NOT TARGET GeoTIFF::GeoTIFF)
    find_package(TIFF REQUIRED)
    add_library(GeoTIFF::GeoTIFF UNKNOWN IMPORTED)
    set_target_properties(GeoTIFF::GeoTIFF PROPERTIES
        IMPORTED_LOCATION "${GeoTIFF_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${GeoTIFF_INCLUDE_DIR}"
        INTERFACE_LINK_LIBRARIES TIFF::TIFF)
endif()
