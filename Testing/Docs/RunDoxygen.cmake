# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
# Build the API reference and fail on any Doxygen warning (its log names the
# header, line and member). -DDOXYGEN= -DCONFIG= -DLOG=
get_filename_component(_dir "${CONFIG}" DIRECTORY)
file(REMOVE "${LOG}")
execute_process(COMMAND "${DOXYGEN}" "${CONFIG}" WORKING_DIRECTORY "${_dir}"
  RESULT_VARIABLE _result OUTPUT_VARIABLE _out ERROR_VARIABLE _err)
if (NOT _result EQUAL 0)
  message(FATAL_ERROR "doxygen failed (${_result}):\n${_out}${_err}")
endif ()
file(READ "${LOG}" _warnings)
string(STRIP "${_warnings}" _warnings)
if (_warnings)
  message(FATAL_ERROR "Doxygen warnings in the public headers:\n${_warnings}")
endif ()
message(STATUS "API reference: ${_dir}/html/index.html, no warnings")
