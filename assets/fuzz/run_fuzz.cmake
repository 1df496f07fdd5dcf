# ctest driver: builds the fuzz project with clang in FUZZ_BUILD_DIR, seeds a corpus from the shared
# test data and the small seeds in corpus/, and runs the fuzzer for FUZZ_SECONDS.
# Variables: SOURCE_DIR (assets/fuzz), FUZZ_BUILD_DIR, SHARED_DATA, CLANGXX, FUZZ_SECONDS.
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${FUZZ_BUILD_DIR} -G Ninja
                        -DCMAKE_CXX_COMPILER=${CLANGXX} -DCMAKE_BUILD_TYPE=RelWithDebInfo
                RESULT_VARIABLE result)
if(result)
  message(FATAL_ERROR "configuring the fuzz build failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${FUZZ_BUILD_DIR} -j2 RESULT_VARIABLE result)
if(result)
  message(FATAL_ERROR "building the fuzz target failed")
endif()
set(corpus ${FUZZ_BUILD_DIR}/corpus)
file(MAKE_DIRECTORY ${corpus})
file(GLOB seeds ${SOURCE_DIR}/corpus/*)
file(COPY ${seeds} ${SHARED_DATA}/gltf/Box_Draco/Box_Draco.glb ${SHARED_DATA}/gltf/car_drc/car.drc DESTINATION ${corpus})
execute_process(COMMAND ${FUZZ_BUILD_DIR}/fuzz_load_model -max_total_time=${FUZZ_SECONDS} -max_len=65536
                        -rss_limit_mb=2048 -timeout=20 -print_final_stats=1 ${corpus}
                RESULT_VARIABLE result)
if(result)
  message(FATAL_ERROR "the loader fuzzer found a problem (exit ${result}); the crashing input is in the working directory")
endif()
