# OpenCV's core, imgproc and photo found without OpenCV's CMake package. Debian ships that package
# only in libopencv-dev, which installs every OpenCV module (and VTK, FFmpeg and GStreamer with
# them); the library needs three, in libopencv-core-dev, libopencv-imgproc-dev and
# libopencv-photo-dev (scripts/install-deps.sh --demo). Defines the imported targets opencv_core,
# opencv_imgproc and opencv_photo, as OpenCV's package does.
find_path(OpenCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4 REQUIRED)
find_path(OpenCV_CONFIG_INCLUDE_DIR opencv2/cvconfig.h PATH_SUFFIXES opencv4 REQUIRED)
set(opencv_dependencies "")
foreach(module core imgproc photo)
  find_library(OpenCV_${module}_LIBRARY opencv_${module} REQUIRED)
  add_library(opencv_${module} SHARED IMPORTED)
  set_target_properties(opencv_${module} PROPERTIES
    IMPORTED_LOCATION ${OpenCV_${module}_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES "${OpenCV_INCLUDE_DIR};${OpenCV_CONFIG_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${opencv_dependencies}")
  list(APPEND opencv_dependencies opencv_${module})
endforeach()
