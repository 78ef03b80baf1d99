# Script mode: writes OUT, a C++ file defining phasmid::embedded::files() from FILES.
# Content is split into raw-string chunks to stay under compiler literal limits.
string(REPLACE "|" ";" FILES "${FILES}")  # Embed.cmake passes the list "|"-joined
set(_body "#include <map>\n#include <string>\nnamespace phasmid::embedded {\nconst std::map<std::string, std::string>& files() {\n  static const std::map<std::string, std::string> table = {\n")
foreach(f ${FILES})
  file(RELATIVE_PATH rel ${ROOT} ${f})
  file(READ ${f} content HEX)
  string(LENGTH "${content}" n)
  set(_bytes "")
  # Hex-encode so any byte (quotes, backslashes, ")") survives.
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "\\\\x\\1" escaped "${content}")
  # Break into string-literal pieces of 4000 escaped bytes.
  string(LENGTH "${escaped}" elen)
  set(_lit "")
  set(pos 0)
  while(pos LESS elen)
    string(SUBSTRING "${escaped}" ${pos} 16000 piece)
    string(APPEND _lit "\"${piece}\"\n")
    math(EXPR pos "${pos} + 16000")
  endwhile()
  if(_lit STREQUAL "")
    set(_lit "\"\"")
  endif()
  string(APPEND _body "    {\"${rel}\", std::string(${_lit}, ${n} / 2)},\n")
endforeach()
string(APPEND _body "  };\n  return table;\n}\n}  // namespace phasmid::embedded\n")
file(WRITE ${OUT} "${_body}")
