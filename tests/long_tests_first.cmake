# Read by ctest after the tests are listed (tests/CMakeLists.txt): the seconds each long test took
# in the sanitized suite (scripts/test_sanitized.sh, 2026-12-02), as its COST, so ctest starts the
# longest first. ctest passes over a name that no longer exists (a renamed test only loses its place).
set(lfcam_long_tests
  "HciAntinousDepth.ScoresAndAllInFocus" 110
  "EveryCommand/CommandExample.RunsFromTheRepositorysRoot/depth  # GetParam() = \"depth\"" 101
  "Cli.DemoExampleWritesAPageAndItsPictures" 87
  "EveryCommand/CommandExample.RunsFromTheRepositorysRoot/export_html  # GetParam() = \"export-html\"" 53
  "DepthViewOffsets.MeasuredWithoutTheMapsErrorLeaveLessOfASheen" 46
  "CliExperiment.ExampleShowsSharpnessGrowingWithN" 41)
list(LENGTH lfcam_long_tests lfcam_count)
math(EXPR lfcam_last "${lfcam_count} - 1")
foreach(i RANGE 0 ${lfcam_last} 2)
  math(EXPR j "${i} + 1")
  list(GET lfcam_long_tests ${i} name)
  list(GET lfcam_long_tests ${j} seconds)
  set_tests_properties("${name}" PROPERTIES COST ${seconds})
endforeach()
