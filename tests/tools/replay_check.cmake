# replay_check.cmake - end-to-end checks of the ht_replay binary, run by ctest
# as `cmake -DMODE=... -DEXE=... [...] -P replay_check.cmake`. Plain CMake, so
# the checks need nothing beyond the build's own tools.
#
# Common variables: EXE (the binary), INPUT (a CSV file), ARGS (arguments,
# separated by '|' because ctest passes one string), WORK (a scratch folder).
#
# MODE=expect   exit 0, empty stderr, the documented header, one well-formed
#               row per input row, and every "row,column,expected,tolerance"
#               line of the file EXPECTED holds (values compared as integers of
#               1e-6, so the check is exact arithmetic, not CMake's float).
# MODE=bad      exit EXPECT_RC, and stderr is one line "ht_replay: ..." that
#               contains EXPECT_STDERR. TRANSFORM=crlf feeds INPUT with CRLF
#               line endings; TRANSFORM=longline feeds a generated header and a
#               data line longer than the 1 MiB limit instead of INPUT.
#               OUTPUT_TO sends stdout to that file (e.g. /dev/full).
# MODE=same     the output for INPUT equals the output for OTHER; with
#               OTHER unset, INPUT is compared with itself rewritten with CRLF
#               endings, with and without a final line ending, and with a
#               UTF-8 byte order mark.
# MODE=help     --help exits 0 and documents the things the README promises.
cmake_minimum_required(VERSION 3.25)

foreach(v MODE EXE)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "replay_check: ${v} is not set")
  endif()
endforeach()
if(NOT DEFINED WORK)
  set(WORK "${CMAKE_CURRENT_BINARY_DIR}")
endif()
file(MAKE_DIRECTORY "${WORK}")
if(DEFINED ARGS)
  string(REPLACE "|" ";" args "${ARGS}")
else()
  set(args "")
endif()

# run(<input file> <prefix>): sets <prefix>_rc, <prefix>_out, <prefix>_err.
function(run input prefix)
  if(DEFINED OUTPUT_TO)
    set(out_opt OUTPUT_FILE "${OUTPUT_TO}")
  else()
    set(out_opt OUTPUT_VARIABLE out)
  endif()
  execute_process(
    COMMAND "${EXE}" ${args}
    INPUT_FILE "${input}"
    ${out_opt}
    ERROR_VARIABLE err
    RESULT_VARIABLE rc
    TIMEOUT 60)
  set(${prefix}_rc "${rc}" PARENT_SCOPE)
  set(${prefix}_out "${out}" PARENT_SCOPE)
  set(${prefix}_err "${err}" PARENT_SCOPE)
endfunction()

# to_micro(<decimal text> <out var>): the value in units of 1e-6 as an
# integer, exactly. At most 6 decimals are allowed (the tool prints 6).
function(to_micro text outvar)
  if(NOT text MATCHES "^(-?)([0-9]+)(\\.([0-9]*))?$")
    message(FATAL_ERROR "not a decimal number: \"${text}\"")
  endif()
  set(sign "${CMAKE_MATCH_1}")
  set(int "${CMAKE_MATCH_2}")
  set(frac "${CMAKE_MATCH_4}")
  string(LENGTH "${frac}" n)
  if(n GREATER 6)
    message(FATAL_ERROR "more than 6 decimals: \"${text}\"")
  endif()
  while(n LESS 6)
    string(APPEND frac "0")
    math(EXPR n "${n} + 1")
  endwhile()
  string(REGEX REPLACE "^0+([0-9])" "\\1" int "${int}")
  string(REGEX REPLACE "^0+" "" frac "${frac}")
  if(frac STREQUAL "")
    set(frac 0)
  endif()
  math(EXPR v "${sign}(${int} * 1000000 + ${frac})")
  set(${outvar} "${v}" PARENT_SCOPE)
endfunction()

# The documented output header (README.md, format.h).
set(HEADER "turn_rate_used,tilt_x,tilt_y,tilt_z,rate_x,rate_y,rate_z,roll_dot,roll_cross,roll_error,pitch_error,pitch_body_x,pitch_body_z,aileron,elevator,rudder,tilt_ratio,flags")

if(MODE STREQUAL "expect")
  run("${INPUT}" r)
  if(NOT r_rc EQUAL 0 OR NOT r_err STREQUAL "")
    message(FATAL_ERROR "ht_replay failed (exit ${r_rc}):\n${r_err}")
  endif()
  string(REGEX REPLACE "\n$" "" body "${r_out}")
  string(REPLACE "\n" ";" lines "${body}")
  list(GET lines 0 header)
  if(NOT header STREQUAL HEADER)
    message(FATAL_ERROR "header is\n  ${header}\nexpected\n  ${HEADER}")
  endif()
  string(REPLACE "," ";" names "${header}")
  list(LENGTH names ncols)

  # One output row per input row.
  file(STRINGS "${INPUT}" in_lines)
  list(LENGTH in_lines n_in)
  list(LENGTH lines n_out)
  if(NOT n_in EQUAL n_out)
    message(FATAL_ERROR "${n_in} input lines but ${n_out} output lines:\n${r_out}")
  endif()

  # Every row: 17 numbers with exactly 6 decimals, then the flags integer.
  math(EXPR last "${n_out} - 1")
  foreach(i RANGE 1 ${last})
    list(GET lines ${i} row)
    if(NOT row MATCHES "^(-?[0-9]+\\.[0-9][0-9][0-9][0-9][0-9][0-9],)+[0-9]+$")
      message(FATAL_ERROR "output row ${i} is malformed: \"${row}\"")
    endif()
    string(REPLACE "," ";" cells "${row}")
    list(LENGTH cells n)
    if(NOT n EQUAL ncols)
      message(FATAL_ERROR "output row ${i} has ${n} cells, the header ${ncols}")
    endif()
  endforeach()

  file(STRINGS "${EXPECTED}" checks REGEX "^[^#]")
  set(failures "")
  set(count 0)
  foreach(check IN LISTS checks)
    string(REPLACE "," ";" c "${check}")
    list(LENGTH c n)
    if(NOT n EQUAL 4)
      message(FATAL_ERROR "bad line in ${EXPECTED}: \"${check}\"")
    endif()
    list(GET c 0 rowno)
    list(GET c 1 col)
    list(GET c 2 want)
    list(GET c 3 tol)
    list(FIND names "${col}" k)
    if(k LESS 0)
      message(FATAL_ERROR "${EXPECTED}: no output column \"${col}\"")
    endif()
    if(rowno LESS 1 OR rowno GREATER last)
      message(FATAL_ERROR "${EXPECTED}: no output row ${rowno}")
    endif()
    list(GET lines ${rowno} row)
    string(REPLACE "," ";" cells "${row}")
    list(GET cells ${k} got)
    to_micro("${got}" g)
    to_micro("${want}" w)
    to_micro("${tol}" t)
    math(EXPR d "${g} - ${w}")
    if(d LESS 0)
      math(EXPR d "-(${d})")
    endif()
    if(d GREATER t)
      string(APPEND failures "\n  row ${rowno} ${col}: got ${got}, expected ${want} +/- ${tol}")
    endif()
    math(EXPR count "${count} + 1")
  endforeach()
  if(count EQUAL 0)
    message(FATAL_ERROR "${EXPECTED} holds no checks")
  endif()
  if(NOT failures STREQUAL "")
    message(FATAL_ERROR "ht_replay ${ARGS} < ${INPUT}:${failures}\nfull output:\n${r_out}")
  endif()
  message(STATUS "${count} values checked")

elseif(MODE STREQUAL "bad")
  if(DEFINED TRANSFORM AND TRANSFORM STREQUAL "longline")
    # 0,0,1, then digits far past the limit: the error falls in turn_rate.
    string(REPEAT "1234567890" 110000 digits)
    file(WRITE "${WORK}/longline.csv"
      "x,y,z,turn_rate,pitch,airspeed,gyro_x,gyro_y,gyro_z,inverted\n0,0,1,${digits},0,15,0,0,0,0\n")
    set(input "${WORK}/longline.csv")
  elseif(DEFINED TRANSFORM AND TRANSFORM STREQUAL "crlf")
    file(READ "${INPUT}" text)
    string(REPLACE "\n" "\r\n" text "${text}")
    get_filename_component(base "${INPUT}" NAME)
    file(WRITE "${WORK}/crlf_${base}" "${text}")
    set(input "${WORK}/crlf_${base}")
  else()
    set(input "${INPUT}")
  endif()
  run("${input}" r)
  if(NOT r_rc STREQUAL EXPECT_RC)
    message(FATAL_ERROR "exit status ${r_rc}, expected ${EXPECT_RC}; stderr:\n${r_err}")
  endif()
  string(FIND "${r_err}" "${EXPECT_STDERR}" at)
  if(at LESS 0)
    message(FATAL_ERROR "stderr lacks \"${EXPECT_STDERR}\":\n${r_err}")
  endif()
  if(NOT r_err MATCHES "^ht_replay: [^\n\r]+\n$")
    message(FATAL_ERROR "stderr is not one clean \"ht_replay: ...\" line:\n[${r_err}]")
  endif()
  message(STATUS "exit ${r_rc}: ${r_err}")

elseif(MODE STREQUAL "same")
  run("${INPUT}" a)
  if(NOT a_rc EQUAL 0)
    message(FATAL_ERROR "ht_replay failed on ${INPUT} (exit ${a_rc}):\n${a_err}")
  endif()
  set(others "")
  if(DEFINED OTHER)
    list(APPEND others "${OTHER}")
  else()
    file(READ "${INPUT}" text)
    string(REGEX REPLACE "\n$" "" stripped "${text}")
    string(REPLACE "\n" "\r\n" crlf "${stripped}")
    string(ASCII 239 187 191 bom)
    file(WRITE "${WORK}/v_crlf.csv" "${crlf}\r\n")
    file(WRITE "${WORK}/v_crlf_noeol.csv" "${crlf}")
    file(WRITE "${WORK}/v_lf_noeol.csv" "${stripped}")
    file(WRITE "${WORK}/v_bom.csv" "${bom}${text}")
    list(APPEND others "${WORK}/v_crlf.csv" "${WORK}/v_crlf_noeol.csv" "${WORK}/v_lf_noeol.csv"
      "${WORK}/v_bom.csv")
  endif()
  foreach(o IN LISTS others)
    run("${o}" b)
    if(NOT b_rc EQUAL 0 OR NOT b_out STREQUAL a_out)
      message(FATAL_ERROR "${o} gives (exit ${b_rc}, ${b_err}):\n${b_out}\n${INPUT} gives:\n${a_out}")
    endif()
  endforeach()
  string(LENGTH "${a_out}" n)
  if(n LESS 200)
    message(FATAL_ERROR "suspiciously short output:\n${a_out}")
  endif()

elseif(MODE STREQUAL "help")
  execute_process(COMMAND "${EXE}" --help
    OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc TIMEOUT 60)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "--help exit ${rc}:\n${err}")
  endif()
  foreach(needle "usage: ht_replay" "not a clamp" "halves away from zero" "400 characters"
      "line N, column NAME" "Exit status"
      kp_aileron kp_elevator kp_rudder kff_aileron kff_elevator kff_rudder kd_aileron
      kd_elevator kd_rudder v_ref v_min schedule max_tilt pitch_mode gyro_z inverted)
    string(FIND "${out}" "${needle}" at)
    if(at LESS 0)
      message(FATAL_ERROR "--help does not mention \"${needle}\":\n${out}")
    endif()
  endforeach()

else()
  message(FATAL_ERROR "replay_check: unknown MODE ${MODE}")
endif()
