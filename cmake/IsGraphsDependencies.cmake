# The third-party C++ libraries whose API changed across the platforms is_graphs supports
# (Debian 11 / Ubuntu 20.04 to Debian 13; docs/platforms.md). Each is found once here and its
# version checked against the supported range, so that a user with another version reads one
# message naming the version found and the range, not a compile error 200 lines later.

# Ceres Solver 1.14 (Ubuntu 20.04, Debian 11) to 2.2 (Debian 13). Sets IS_GRAPHS_CERES_TARGET.
# 1.14 exports the target `ceres`, 2.x `Ceres::ceres`; include/is_graphs/common/ceres_compat.h
# hides the Manifold / LocalParameterization change of 2.1.
macro(is_graphs_find_ceres)
  find_package(Ceres QUIET)
  if(NOT Ceres_FOUND)
    message(FATAL_ERROR "is_graphs: Ceres Solver not found; it needs Ceres 1.14 to 2.2 "
                        "(Debian/Ubuntu: apt-get install libceres-dev; rosdep key libceres-dev)")
  endif()
  set(_is_graphs_ceres_version "${Ceres_VERSION}")
  if(NOT _is_graphs_ceres_version)
    set(_is_graphs_ceres_version "${CERES_VERSION}")
  endif()
  if(_is_graphs_ceres_version VERSION_LESS 1.14)
    message(FATAL_ERROR "is_graphs: Ceres ${_is_graphs_ceres_version} found (${Ceres_DIR}); "
                        "supported: 1.14 to 2.2")
  elseif(_is_graphs_ceres_version VERSION_GREATER_EQUAL 2.3)
    message(WARNING "is_graphs: Ceres ${_is_graphs_ceres_version} found; tested with 1.14 to "
                    "2.2: a newer Ceres may have changed an API the project uses")
  endif()
  if(TARGET Ceres::ceres)
    set(IS_GRAPHS_CERES_TARGET Ceres::ceres)
  elseif(TARGET ceres)
    set(IS_GRAPHS_CERES_TARGET ceres)
  else()
    set(IS_GRAPHS_CERES_TARGET ${CERES_LIBRARIES})
    include_directories(SYSTEM ${CERES_INCLUDE_DIRS})
  endif()
  message(STATUS "is_graphs: Ceres ${_is_graphs_ceres_version} (${IS_GRAPHS_CERES_TARGET})")
endmacro()

# Embree 3 (Debian 11/12, Ubuntu) or 4 (Debian 13, where 3 is gone). Sets IS_GRAPHS_EMBREE_MAJOR
# for src/core/sim/embree_scene.cpp, the one file that includes Embree.
macro(is_graphs_find_embree)
  find_package(embree 4 QUIET)
  if(NOT embree_FOUND)
    find_package(embree 3 QUIET)
  endif()
  if(NOT embree_FOUND)
    message(FATAL_ERROR "is_graphs: Embree not found; it needs Embree 3 or 4 "
                        "(Debian/Ubuntu: apt-get install libembree-dev; rosdep key embree)")
  endif()
  string(REGEX MATCH "^[0-9]+" IS_GRAPHS_EMBREE_MAJOR "${embree_VERSION}")
  if(NOT IS_GRAPHS_EMBREE_MAJOR MATCHES "^[34]$")
    message(FATAL_ERROR "is_graphs: Embree ${embree_VERSION} found (${embree_DIR}); supported: "
                        "3.x and 4.x")
  endif()
  message(STATUS "is_graphs: Embree ${embree_VERSION}")
endmacro()

# PCL 1.10 (Ubuntu 20.04) to 1.15 (Debian 13), with the given components.
macro(is_graphs_find_pcl)
  find_package(PCL QUIET COMPONENTS ${ARGN})
  if(NOT PCL_FOUND)
    message(FATAL_ERROR "is_graphs: PCL (components ${ARGN}) not found; it needs PCL 1.10 to "
                        "1.15 (Debian/Ubuntu: apt-get install libpcl-dev)")
  endif()
  if(PCL_VERSION VERSION_LESS 1.10)
    message(FATAL_ERROR "is_graphs: PCL ${PCL_VERSION} found (${PCL_DIR}); supported: 1.10 to 1.15")
  elseif(PCL_VERSION VERSION_GREATER_EQUAL 1.16)
    message(WARNING "is_graphs: PCL ${PCL_VERSION} found; tested with 1.10 to 1.15")
  endif()
  message(STATUS "is_graphs: PCL ${PCL_VERSION}")
endmacro()
