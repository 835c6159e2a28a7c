# Every dependency is a Debian bookworm package (installed by scripts/setup.sh).

# Debian's PCL and Ceres are built for plain x86-64 (16-byte Eigen alignment):
# keep the whole project on that ABI whatever -march is used.
add_compile_definitions(EIGEN_MAX_ALIGN_BYTES=16)

find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(yaml-cpp REQUIRED)          # target yaml-cpp (no namespace in 0.7)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(Boost REQUIRED COMPONENTS filesystem)

# ROS1 rosbag from Debian (no ROS install); its pkg-config file is broken, so
# the imported target is assembled here.
set(_ros_libs rosbag_storage roscpp_serialization rostime cpp_common console_bridge roslz4)
set(_ros_paths)
foreach(lib IN LISTS _ros_libs)
  find_library(STOREY_${lib}_LIBRARY NAMES ${lib} REQUIRED)
  list(APPEND _ros_paths ${STOREY_${lib}_LIBRARY})
endforeach()
find_path(STOREY_ROSBAG_INCLUDE_DIR rosbag/bag.h REQUIRED)
add_library(storey_rosbag INTERFACE)
target_include_directories(storey_rosbag SYSTEM INTERFACE
  ${STOREY_ROSBAG_INCLUDE_DIR}
  /usr/include/pluginlib /usr/include/class_loader /usr/include/rcutils
  /usr/include/rcpputils /usr/include/ament_index_cpp)
target_link_libraries(storey_rosbag INTERFACE ${_ros_paths} Boost::filesystem)
