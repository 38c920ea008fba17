# Writes OUT, a C++ header holding the timeline page's markup (HTML) and
# script as raw string literals, so that `bsc timeline` needs no files beside
# it.  cmake -DHTML=page.html -DJS="a.js;b.js;..." -DOUT=... -P EmbedPage.cmake
#
# JS is a list of the script's files in order. They are concatenated into one
# strict-mode function, so that they share one scope of plain function
# declarations and top-level let/const without leaking into the window.
file(READ "${HTML}" PAGE_HTML)
string(FIND "${PAGE_HTML}" ")bsc_page\"" AT)
if(NOT AT EQUAL -1)
  message(FATAL_ERROR "${HTML} holds the raw string's end ')bsc_page\"'")
endif()
set(PAGE_JS "(function () {\n'use strict';\n")
foreach(FILE IN LISTS JS)
  file(READ "${FILE}" TEXT)
  string(FIND "${TEXT}" ")bsc_page\"" AT)
  if(NOT AT EQUAL -1)
    message(FATAL_ERROR "${FILE} holds the raw string's end ')bsc_page\"'")
  endif()
  string(APPEND PAGE_JS "${TEXT}")
endforeach()
string(APPEND PAGE_JS "\n})();\n")
file(WRITE "${OUT}.tmp"
  "// Generated from lib/Timeline/page by EmbedPage.cmake; do not edit.\n"
  "static const char PageHTML[] = R\"bsc_page(${PAGE_HTML})bsc_page\";\n"
  "static const char PageScript[] = R\"bsc_page(${PAGE_JS})bsc_page\";\n")
file(COPY_FILE "${OUT}.tmp" "${OUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUT}.tmp")
