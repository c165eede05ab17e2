# Included right after project() of each CMake package `make setup` builds (CMAKE_PROJECT_INCLUDE):
# the interface packages get only the generators their Python users need. The venv holds no rclcpp,
# so nothing here can use C++ message code; dropping its four generators (headers, C++ type support,
# Fast DDS and introspection for C++) halves the build's CPU time. Python's messages need the C
# ones: the C structs, the type-support dispatcher with its Fast DDS and introspection back ends,
# and the type descriptions. A student's own `colcon build` of a course package is unaffected.
find_package(rosidl_default_generators QUIET)
list(FILTER AMENT_EXTENSIONS_rosidl_generate_idl_interfaces EXCLUDE REGEX
  "^rosidl_(generator|typesupport|typesupport_fastrtps|typesupport_introspection)_cpp:")
