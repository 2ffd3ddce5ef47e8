# Idle-time estimator, mixing scheduler and the record of their persisted
# state (firmware/core/idle_estimator, mixing_scheduler, state_store): pure,
# freestanding. Included from firmware/CMakeLists.txt.
add_library(mrd_fw_idle STATIC
  ${CMAKE_CURRENT_LIST_DIR}/core/idle_estimator.cpp
  ${CMAKE_CURRENT_LIST_DIR}/core/mixing_scheduler.cpp
)
target_include_directories(mrd_fw_idle PUBLIC ${PROJECT_SOURCE_DIR})
target_link_libraries(mrd_fw_idle PUBLIC mrd_common)

if(MRD_BUILD_TESTS)
  find_package(ZLIB REQUIRED)  # crc32() as the independent check of the record CRC
  add_executable(mrd_fw_idle_tests
    ${PROJECT_SOURCE_DIR}/tests/unit/idle_estimator_test.cpp
    ${PROJECT_SOURCE_DIR}/tests/unit/mixing_scheduler_test.cpp
    ${PROJECT_SOURCE_DIR}/tests/unit/state_store_test.cpp
  )
  target_link_libraries(mrd_fw_idle_tests PRIVATE mrd_fw_idle mrd_platform_linux mrd_platform_sim ZLIB::ZLIB
    GTest::gtest_main)
  gtest_discover_tests(mrd_fw_idle_tests DISCOVERY_MODE PRE_TEST PROPERTIES LABELS unit)

  # Bare-metal Cortex-M4F compile of the estimator and the scheduler:
  # freestanding, no heap, no exceptions, no stdio.
  find_program(MRD_ARM_GXX arm-none-eabi-g++)
  foreach(unit idle_estimator mixing_scheduler)
    add_test(NAME idle_cross_cortex_m4_${unit}
      COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/idle_cross_check.sh "${MRD_ARM_GXX}"
        ${CMAKE_CURRENT_LIST_DIR}/core/${unit}.cpp
        ${CMAKE_CURRENT_BINARY_DIR}/cortex_m4_${unit}.o
        ${PROJECT_SOURCE_DIR} ${PROJECT_SOURCE_DIR}/common/include)
    set_tests_properties(idle_cross_cortex_m4_${unit} PROPERTIES LABELS cross)
  endforeach()
endif()

if(MRD_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
  add_executable(mrd_bench_idle ${PROJECT_SOURCE_DIR}/bench/idle_bench.cpp)
  target_link_libraries(mrd_bench_idle PRIVATE mrd_fw_idle benchmark::benchmark)
endif()
