# cmake -DPROGRAM=path -DOUTPUT=file.h2m -P commands.cmake
# For a program with commands (its --help has a "Commands:" list of
# "  NAME  summary" lines), write a help2man include file with a COMMANDS
# section holding each `PROGRAM NAME --help`, verbatim, so that the man page
# has every command's options from the program itself. A program without a
# command list gets an include file that adds nothing.
execute_process(COMMAND ${PROGRAM} --help OUTPUT_VARIABLE _help RESULT_VARIABLE _rc)
if(_rc)
  message(FATAL_ERROR "${PROGRAM} --help failed (${_rc})")
endif()
string(REPLACE ";" "\\;" _help "${_help}")
string(REPLACE "\n" ";" _lines "${_help}")
set(_commands "")
set(_in OFF)
foreach(_line IN LISTS _lines)
  if(_line MATCHES "^Commands:")
    set(_in ON)
  elseif(_in AND _line MATCHES "^  +([a-z][a-z0-9-]*)  ")
    list(APPEND _commands ${CMAKE_MATCH_1})
  elseif(_in)
    set(_in OFF)
  endif()
endforeach()

# help2man refuses an include file without a section: an empty addition
# to DESCRIPTION changes nothing.
set(_out "[>DESCRIPTION]\n")
if(_commands)
  get_filename_component(_name ${PROGRAM} NAME)
  set(_out "[COMMANDS]\nEach command's own help, as \\fB${_name} \\fICOMMAND\\fB --help\\fR prints it.\n")
  foreach(_cmd IN LISTS _commands)
    execute_process(COMMAND ${PROGRAM} ${_cmd} --help OUTPUT_VARIABLE _text RESULT_VARIABLE _rc)
    if(_rc)
      message(FATAL_ERROR "${PROGRAM} ${_cmd} --help failed (${_rc})")
    endif()
    # roff: a backslash is \e; a line starting with . or ' would be a request.
    string(REPLACE "\\" "\\e" _text "${_text}")
    string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" _text "${_text}")
    string(APPEND _out ".SS \"${_name} ${_cmd}\"\n.nf\n${_text}.fi\n")
  endforeach()
endif()
file(WRITE ${OUTPUT}.new "${_out}")
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different ${OUTPUT}.new ${OUTPUT})
file(REMOVE ${OUTPUT}.new)
