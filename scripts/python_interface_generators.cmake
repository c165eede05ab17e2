# Included right after project() of each CMake package `make setup` builds (CMAKE_PROJECT_INCLUDE):
# the interface packages get only the generators their Python users need. The venv holds no rclcpp,
# so nothing here can use C++ message code; dropping its four generators (headers, C++ type support,
# Fast DDS and introspection for C++) halves the build's CPU time. Python's messages need the C
# ones: the C structs, the type-support dispatcher with its Fast DDS and introspection back ends,
# and the type descriptions. A student's own `colcon build` of a course package is unaffected.
find_package(rosidl_default_generators QUIET)
list(FILTER AMENT_EXTENSIONS_rosidl_generate_idl_interfaces EXCLUDE REGEX
  "^rosidl_(generator|typesupport|typesupport_fastrtps|typesupport_introspection)_cpp:")

# The generated C files of an interface package build as a few unity files (CMake's UNITY_BUILD)
# rather than one compiler run each: example_interfaces took 34 s alone, now 21 s. The type
# description files stay apart: each defines the same static names as the next.
function(_owl_unity_interface_targets)
  get_property(targets DIRECTORY PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target IN LISTS targets)
    if(target MATCHES "__rosidl_|__python$")
      set_property(TARGET ${target} PROPERTY UNITY_BUILD ON)
      get_target_property(sources ${target} SOURCES)
      foreach(source IN LISTS sources)
        if(source MATCHES "__description\\.c$")
          set_property(SOURCE ${source} PROPERTY SKIP_UNITY_BUILD_INCLUSION ON)
        endif()
      endforeach()
    endif()
  endforeach()
endfunction()
cmake_language(DEFER CALL _owl_unity_interface_targets)
