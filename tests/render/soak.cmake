# The headless renderer's soak: 2,000 frames of the default scene in one process (small images,
# so it takes seconds), and its resident memory must stay flat.
#
#   cmake -DSOFTBODY=<softbody> -DWORK=<folder for the frames> -P soak.cmake
#
# Each JSON line carries the process's resident memory after its frame. The first frames
# allocate what every later frame reuses (shader variants, buffers, the allocator's pools), so
# memory is compared from frame 200 on. Measured: a single step of about 1 MiB near frame 1,000
# (the C library moving a freed block's size class from mmap to its heap), then flat to frame
# 8,000. The allowance, 4 MiB over 1,800 frames, fails any leak of more than about 2.3 KiB a
# frame: one 64x48 image (12 KiB), one vertex buffer or one PNG buffer per frame.
cmake_minimum_required(VERSION 3.25)
set(frames 2000)
set(from_frame 200)
set(allowance_kib 4096)

file(REMOVE_RECURSE ${WORK})
execute_process(
  COMMAND ${SOFTBODY} render --frames ${frames} --fps 60 --size 64x48 --samples 1 --out ${WORK}
  RESULT_VARIABLE rc OUTPUT_VARIABLE json ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "softbody render failed (exit ${rc}):\n${err}")
endif()

string(REGEX MATCHALL "\"memory_kib\":[0-9]+" memory "${json}")
list(LENGTH memory lines)
if(NOT lines EQUAL frames)
  message(FATAL_ERROR "expected ${frames} JSON lines with memory_kib, got ${lines}")
endif()
list(TRANSFORM memory REPLACE "\"memory_kib\":" "")
list(GET memory 0 first)
list(GET memory ${from_frame} start)
list(GET memory -1 end)
math(EXPR growth "${end} - ${start}")
message(STATUS "resident memory: ${first} KiB after frame 0, ${start} KiB after frame ${from_frame}, "
               "${end} KiB after frame ${frames} (growth ${growth} KiB, allowed ${allowance_kib})")
if(growth GREATER allowance_kib)
  message(FATAL_ERROR "memory grew by ${growth} KiB from frame ${from_frame} to ${frames}")
endif()

# Every frame written, numbered so that name order is frame order.
math(EXPR last "${frames} - 1")
foreach(k 0000 0001 ${last})
  if(NOT EXISTS ${WORK}/default_${k}.png)
    message(FATAL_ERROR "frame ${WORK}/default_${k}.png is missing")
  endif()
endforeach()
file(GLOB written ${WORK}/*.png)
list(LENGTH written count)
if(NOT count EQUAL frames)
  message(FATAL_ERROR "expected ${frames} PNG files, found ${count}")
endif()
file(REMOVE_RECURSE ${WORK})
