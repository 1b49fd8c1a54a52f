# embed_text(FILE SYMBOL HEADER): writes HEADER declaring `inline constexpr const char SYMBOL[]`
# holding FILE's text as a raw string literal, so the binary carries the file and the repository
# keeps one copy of it. Re-runs at build time when FILE changes (it is a configure dependency).
function(embed_text file symbol header)
  file(READ "${file}" text)
  set(delimiter "dp_embed")
  string(FIND "${text}" ")${delimiter}\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${file} contains the raw-string delimiter )${delimiter}\"")
  endif()
  set(content "// Generated from ${file} by cmake/EmbedText.cmake: edit that file, not this one.\n#pragma once\n\n")
  string(APPEND content "inline constexpr const char ${symbol}[] = R\"${delimiter}(${text})${delimiter}\";\n")
  # Written only when it changes, so that an unrelated re-configure rebuilds nothing.
  set(old "")
  if(EXISTS "${header}")
    file(READ "${header}" old)
  endif()
  if(NOT old STREQUAL content)
    file(WRITE "${header}" "${content}")
  endif()
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${file}")
endfunction()
