# Renders screenshot cases and compares them with their references, or re-blesses them.
# Run by CTest (one case per test) and by the bless-screenshots target:
#
#   cmake -DMODE=test|negative|noise|bless -DCASE=<name> -DSOFTBODY=<softbody> -DCOMPARE=<compare tool>
#         -DWORK=<build folder for images> -P screenshot.cmake
#
#   test      render CASE, compare with references/CASE.png; on failure the actual, expected and
#             diff images go to WORK/failures and are named in the output
#   negative  render the fault NEGATIVE_<CASE> (cases.cmake); passes only if the comparison FAILS
#   noise     render CASE with llvmpipe's SIMD extensions off (another CPU's rounding); must match
#   same      render CASE twice (1 and 4 rendering threads, 1 and 2 physics threads): the PNG files
#             must be byte-identical
#   bless     render every case (or CASE) into references/: the one deliberate way to change them
cmake_minimum_required(VERSION 3.25)
set(HERE ${CMAKE_CURRENT_LIST_DIR})
include(${HERE}/cases.cmake)
foreach(var MODE SOFTBODY WORK)
  if(NOT ${var})
    message(FATAL_ERROR "screenshot.cmake needs -D${var}=...")
  endif()
endforeach()

# Relative paths are taken from where the script was started (the commands run in ${HERE}).
foreach(var SOFTBODY WORK COMPARE)
  if(${var})
    get_filename_component(${var} "${${var}}" ABSOLUTE)
  endif()
endforeach()

# Renders one case with extra arguments; sets <out_var> to the PNG written.
function(render_case name case_args out_var)
  set(out_dir ${WORK}/actual/${name})
  file(REMOVE_RECURSE ${out_dir})
  execute_process(
    COMMAND ${ENV_PREFIX} ${SOFTBODY} render --size ${SCREENSHOT_SIZE} ${case_args} --out ${out_dir}
    WORKING_DIRECTORY ${HERE}
    RESULT_VARIABLE rc OUTPUT_VARIABLE json ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: softbody render failed (exit ${rc}):\n${err}")
  endif()
  string(JSON file ERROR_VARIABLE json_error GET "${json}" file)
  if(json_error OR NOT EXISTS "${file}")
    message(FATAL_ERROR "${name}: softbody render printed no image line:\n${json}\n${err}")
  endif()
  set(${out_var} ${file} PARENT_SCOPE)
endfunction()

function(compare name actual reference)
  execute_process(
    COMMAND ${COMPARE} ${actual} ${reference} --name ${name} --failures ${WORK}/failures ${ARGN}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: screenshot test failed. If the new picture is the intended one, "
                        "re-bless on purpose: cmake --build <build folder> --target bless-screenshots "
                        "(see tests/render/README.md)")
  endif()
endfunction()

if(MODE STREQUAL "bless")
  set(cases ${SCREENSHOT_CASES})
  if(CASE)
    set(cases ${CASE})
  endif()
  foreach(name IN LISTS cases)
    render_case(${name} "${CASE_${name}}" file)
    file(COPY_FILE ${file} ${HERE}/references/${name}.png)
    file(SIZE ${HERE}/references/${name}.png bytes)
    message("blessed references/${name}.png (${bytes} bytes)")
  endforeach()
elseif(MODE STREQUAL "test")
  file(REMOVE ${WORK}/failures/${CASE}_actual.png ${WORK}/failures/${CASE}_expected.png ${WORK}/failures/${CASE}_diff.png)
  render_case(${CASE} "${CASE_${CASE}}" file)
  compare(${CASE} ${file} ${HERE}/references/${CASE}.png)
elseif(MODE STREQUAL "noise")
  # llvmpipe compiles its shaders for the CPU it runs on; told to use no SIMD extensions at all,
  # it rounds a little differently, as on another machine (here: at most 1 level in a channel).
  set(ENV_PREFIX ${CMAKE_COMMAND} -E env GALLIUM_OVERRIDE_CPU_CAPS=nosse)
  render_case(noise_${CASE} "${CASE_${CASE}}" file)
  compare(noise_${CASE} ${file} ${HERE}/references/${CASE}.png)
elseif(MODE STREQUAL "same")
  set(ENV_PREFIX ${CMAKE_COMMAND} -E env LP_NUM_THREADS=1)
  render_case(same_a_${CASE} "${CASE_${CASE}};--threads;1" first)
  set(ENV_PREFIX ${CMAKE_COMMAND} -E env LP_NUM_THREADS=4)
  render_case(same_b_${CASE} "${CASE_${CASE}};--threads;2" second)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${first} ${second} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${CASE}: the same inputs gave different PNG files:\n  ${first}\n  ${second}")
  endif()
  message("${CASE}: byte-identical PNG files from two runs")
elseif(MODE STREQUAL "negative")
  set(fault ${NEGATIVE_${CASE}})
  list(POP_FRONT fault base)
  render_case(fault_${CASE} "${CASE_${base}};${fault}" file)
  compare(fault_${CASE} ${file} ${HERE}/references/${base}.png --expect-different)
else()
  message(FATAL_ERROR "MODE must be test, negative, noise, same or bless, not '${MODE}'")
endif()
