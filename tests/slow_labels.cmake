# Read by CTest after the Catch2 discoveries (tests/CMakeLists.txt): the
# tests tagged [slow] get the labels cpp and slow.
foreach(test IN LISTS impactkit_slow_tests)
  set_tests_properties("${test}" PROPERTIES LABELS "cpp;slow")
endforeach()
