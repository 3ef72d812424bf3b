# ctest foreign_gcs.bad_input: usage errors exit 2, bad files exit 1 with one line naming the
# problem, and no output file is left behind.  -D: FOREIGN_GCS WORK NAME
cmake_minimum_required(VERSION 3.20)
set(dir ${WORK}/${NAME})
file(MAKE_DIRECTORY ${dir})
file(WRITE ${dir}/ok.xyz "0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n")
file(WRITE ${dir}/nan.xyz "0 0 0\n1 0 0\nnan 1 0\n0 0 1\n")
file(WRITE ${dir}/mixed.xyz "0 0 0\n1 0 0\n0 1 0 0 0 1\n0 0 1\n")
file(WRITE ${dir}/word.xyz "0 0 0\n1 0 x\n0 1 0\n0 0 1\n")
file(WRITE ${dir}/few.xyz "0 0 0\n1 0 0\n")
file(WRITE ${dir}/same.xyz "1 1 1\n1 1 1\n1 1 1\n1 1 1\n")
file(WRITE ${dir}/zero-normal.xyz "0 0 0 0 0 0\n1 0 0 0 0 1\n0 1 0 0 0 1\n0 0 1 0 0 1\n")
set(out ${dir}/out.off)
# case: expected exit code | expected text | arguments separated by commas
set(cases
  "2|--vertices: 5 is out of range|${dir}/ok.xyz,-o,${out},--vertices,5"
  "2|--seed: '-1' is not a non-negative integer|${dir}/ok.xyz,-o,${out},--seed,-1"
  "2|must end in .off or .ply|${dir}/ok.xyz,-o,${dir}/out.txt"
  "2|unknown option --frobnicate|${dir}/ok.xyz,-o,${out},--frobnicate"
  "2|--heal-gap: '-1' is not a number in|${dir}/ok.xyz,-o,${out},--heal,--heal-gap,-1"
  "2|--heal-gap: 'x' is not a number in|${dir}/ok.xyz,-o,${out},--heal,--heal-gap,x"
  "1|--heal needs oriented points|${dir}/ok.xyz,-o,${out},--heal"
  "2|--grow: 9 is out of range|${dir}/ok.xyz,-o,${out},--grow,9"
  "2|--min-piece: '0.7' is not a number in|${dir}/ok.xyz,-o,${out},--heal,--min-piece,0.7"
  "1|--heal needs oriented points|${dir}/ok.xyz,-o,${out},--grow,1"
  "2|-o MESH is required|${dir}/ok.xyz"
  "2|is not a directory|${dir}/ok.xyz,-o,${dir}/missing/out.off"
  "1|not a regular file|${dir}/missing.xyz,-o,${out}"
  "1|nan.xyz:3: 'nan' is not a finite number|${dir}/nan.xyz,-o,${out}"
  "1|mixed.xyz:3: 6 values where earlier lines have 3|${dir}/mixed.xyz,-o,${out}"
  "1|word.xyz:2: 'x' is not a number|${dir}/word.xyz,-o,${out}"
  "1|fewer than 4 points|${dir}/few.xyz,-o,${out}"
  "1|all points coincide|${dir}/same.xyz,-o,${out}"
  "1|zero-normal.xyz:1: zero normal|${dir}/zero-normal.xyz,-o,${out}")
set(failures "")
foreach(c IN LISTS cases)
  string(REPLACE "," ";" c "${c}")
  string(REPLACE "|" ";" parts "${c}")
  list(GET parts 0 want_rc)
  list(GET parts 1 want_text)
  list(SUBLIST parts 2 -1 args)
  file(REMOVE ${out})
  execute_process(COMMAND ${FOREIGN_GCS} ${args} RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  string(FIND "${err}" "${want_text}" at)
  if(NOT rc EQUAL want_rc OR at EQUAL -1 OR EXISTS ${out})
    list(APPEND failures "[${args}] exit ${rc} (want ${want_rc}), stderr: ${err}")
  endif()
endforeach()
# The same program on a good file writes a mesh (the cases above fail for their own reason).
execute_process(COMMAND ${FOREIGN_GCS} ${dir}/ok.xyz -o ${out} --vertices 6 RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS ${out})
  list(APPEND failures "the good file failed: exit ${rc}: ${err}")
endif()
file(GLOB leftovers ${dir}/*.tmp-*)
if(leftovers)
  list(APPEND failures "temporary files left: ${leftovers}")
endif()
if(failures)
  string(REPLACE ";" "\n" failures "${failures}")
  message(FATAL_ERROR "${failures}")
endif()
