# Writes OUT, a C++ header holding the timeline page's markup (HTML) and
# script (JS) as raw string literals, so that `bsc timeline` needs no
# files beside it.  cmake -DHTML=... -DJS=... -DOUT=... -P EmbedPage.cmake
file(READ "${HTML}" PAGE_HTML)
file(READ "${JS}" PAGE_JS)
foreach(TEXT PAGE_HTML PAGE_JS)
  string(FIND "${${TEXT}}" ")bsc_page\"" AT)
  if(NOT AT EQUAL -1)
    message(FATAL_ERROR "${TEXT} holds the raw string's end ')bsc_page\"'")
  endif()
endforeach()
file(WRITE "${OUT}.tmp"
  "// Generated from lib/Timeline/page by EmbedPage.cmake; do not edit.\n"
  "static const char PageHTML[] = R\"bsc_page(${PAGE_HTML})bsc_page\";\n"
  "static const char PageScript[] = R\"bsc_page(${PAGE_JS})bsc_page\";\n")
file(COPY_FILE "${OUT}.tmp" "${OUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUT}.tmp")
