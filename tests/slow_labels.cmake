# Read by CTest after the Catch2 discoveries (tests/CMakeLists.txt): the
# tests tagged [slow] get the labels cpp and slow, and a cost (an estimate
# in seconds) that makes `ctest -j` start them before the short ones, so
# that the short ones fill the other core instead of waiting behind them.
foreach(test IN LISTS impactkit_slow_tests)
  set_tests_properties("${test}" PROPERTIES LABELS "cpp;slow" COST 100)
endforeach()
