# mavgen.cmake - the MAVLink 2 C headers, generated at build time by the
# pinned pymavlink's own generator (mavgen) from the common.xml that the
# package installs: no hand-written message, no vendored copy.
#
#   include(mavgen)      -> target ht_mavlink (INTERFACE): link it to use
#                           #include "mavlink/common/mavlink.h"
#
# The headers land in ${CMAKE_BINARY_DIR}/generated/mavlink; they are a
# SYSTEM include directory (our warning flags do not apply to them, nor the
# static analysis: docs/static-analysis.md). The configuration macros every
# user must agree on are compile definitions of ht_mavlink:
#   MAVLINK_NO_CONVERSION_HELPERS  no float conversion helpers (mavlink_conversions.h)
#   MAVLINK_NO_SIGN_PACKET, MAVLINK_NO_SIGNATURE_CHECK  no SHA-256: the link
#                                  drops signed frames (fw_link_rx.c)
# (Not MAVLINK_CHECK_MESSAGE_LENGTH: MAVLink 2 trims a payload's trailing
# zeros, so a valid frame may be shorter than its id's minimum length.)
#
# HT_MAVGEN_PYTHON is the interpreter that has pymavlink: by default the
# project's venv (scripts/setup_venv.sh creates it, with the version pinned
# in sil/requirements-mavlink.lock, before any cmake run). Configure fails,
# saying what to do, when it has no pymavlink or another version.
include_guard(GLOBAL)

set(HT_MAVGEN_PYTHON "${CMAKE_SOURCE_DIR}/.venv/bin/python"
    CACHE FILEPATH "Python with the pinned pymavlink, whose mavgen generates the MAVLink C headers")

# the pinned version, from the lock file
file(STRINGS "${CMAKE_SOURCE_DIR}/sil/requirements-mavlink.lock" _ht_pin REGEX "^pymavlink==")
string(REGEX REPLACE "^pymavlink==" "" HT_MAVGEN_PYMAVLINK_VERSION "${_ht_pin}")
if(HT_MAVGEN_PYMAVLINK_VERSION STREQUAL "")
  message(FATAL_ERROR "mavgen: no 'pymavlink==' line in sil/requirements-mavlink.lock")
endif()

execute_process(
  COMMAND "${HT_MAVGEN_PYTHON}" -c
    "import os, pymavlink; print(getattr(pymavlink, '__version__', '?')); print(os.path.dirname(pymavlink.__file__))"
  RESULT_VARIABLE _ht_rc OUTPUT_VARIABLE _ht_out ERROR_VARIABLE _ht_err
  OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT _ht_rc EQUAL 0)
  message(FATAL_ERROR
    "mavgen: '${HT_MAVGEN_PYTHON}' cannot import pymavlink (needed to generate the MAVLink "
    "headers of the ground-station link). Run scripts/setup_venv.sh first, or pass "
    "-DHT_MAVGEN_PYTHON=/path/to/python with pymavlink==${HT_MAVGEN_PYMAVLINK_VERSION}.\n${_ht_err}")
endif()
string(REPLACE "\n" ";" _ht_out "${_ht_out}")
list(GET _ht_out 0 _ht_version)
list(GET _ht_out 1 _ht_pkg)
if(NOT _ht_version STREQUAL HT_MAVGEN_PYMAVLINK_VERSION)
  message(FATAL_ERROR
    "mavgen: '${HT_MAVGEN_PYTHON}' has pymavlink ${_ht_version}, the pin is "
    "${HT_MAVGEN_PYMAVLINK_VERSION} (sil/requirements-mavlink.lock): run scripts/setup_venv.sh")
endif()

# The package's own definitions: message_definitions/v1.0 in a source tree,
# dialects/v20 in the wheel (the same files; common.xml includes standard.xml
# and minimal.xml from its directory).
set(HT_MAVLINK_XML "")
foreach(_ht_dir "${_ht_pkg}/message_definitions/v1.0" "${_ht_pkg}/dialects/v20")
  if(HT_MAVLINK_XML STREQUAL "" AND EXISTS "${_ht_dir}/common.xml")
    set(HT_MAVLINK_XML "${_ht_dir}/common.xml")
    set(_ht_xml_dir "${_ht_dir}")
  endif()
endforeach()
if(HT_MAVLINK_XML STREQUAL "")
  message(FATAL_ERROR "mavgen: pymavlink ${_ht_version} at ${_ht_pkg} has no common.xml "
                      "(looked in message_definitions/v1.0 and dialects/v20)")
endif()
message(STATUS "mavgen: pymavlink ${_ht_version}, ${HT_MAVLINK_XML}")

set(HT_MAVLINK_GEN_DIR "${CMAKE_BINARY_DIR}/generated")
set(_ht_out_dir "${HT_MAVLINK_GEN_DIR}/mavlink")
set(_ht_outputs
  "${_ht_out_dir}/common/mavlink.h"
  "${_ht_out_dir}/common/common.h"
  "${_ht_out_dir}/minimal/minimal.h"
  "${_ht_out_dir}/standard/standard.h"
  "${_ht_out_dir}/mavlink_helpers.h"
  "${_ht_out_dir}/mavlink_types.h"
  "${_ht_out_dir}/protocol.h"
  "${_ht_out_dir}/checksum.h")
set(_ht_xml_deps "${HT_MAVLINK_XML}")
foreach(_ht_inc standard.xml minimal.xml)
  if(EXISTS "${_ht_xml_dir}/${_ht_inc}")
    list(APPEND _ht_xml_deps "${_ht_xml_dir}/${_ht_inc}")
  endif()
endforeach()

add_custom_command(
  OUTPUT ${_ht_outputs}
  COMMAND "${CMAKE_COMMAND}" -E rm -rf "${_ht_out_dir}"
  COMMAND "${HT_MAVGEN_PYTHON}" -m pymavlink.tools.mavgen --lang=C --wire-protocol=2.0
          -o "${_ht_out_dir}" "${HT_MAVLINK_XML}"
  DEPENDS ${_ht_xml_deps}
  COMMENT "mavgen: MAVLink 2 C headers from ${HT_MAVLINK_XML}"
  VERBATIM)
add_custom_target(ht_mavlink_gen DEPENDS ${_ht_outputs})

add_library(ht_mavlink INTERFACE)
target_include_directories(ht_mavlink SYSTEM INTERFACE "${HT_MAVLINK_GEN_DIR}")
target_compile_definitions(ht_mavlink INTERFACE
  MAVLINK_NO_CONVERSION_HELPERS MAVLINK_NO_SIGN_PACKET MAVLINK_NO_SIGNATURE_CHECK)
add_dependencies(ht_mavlink ht_mavlink_gen)
