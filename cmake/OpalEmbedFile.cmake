# Embeds a file into C++ source (run with cmake -P):
#   -DINPUT=file -DOUTPUT=file.cxx -DFUNCTION=name -DKIND=spirv|text -DHEADER=declaring header
# spirv: defines opal::embedded::Spirv FUNCTION() over the file's 32-bit words.
# text:  defines const char* FUNCTION() returning the file's text.
file(READ "${INPUT}" content HEX)
string(LENGTH "${content}" hex_length)
if (KIND STREQUAL "spirv")
  math(EXPR word_count "${hex_length} / 8")
  # SPIR-V words are little-endian on disk: reorder each word's bytes.
  string(REGEX REPLACE "([0-9a-f][0-9a-f])([0-9a-f][0-9a-f])([0-9a-f][0-9a-f])([0-9a-f][0-9a-f])"
    "0x\\4\\3\\2\\1u," words "${content}")
  file(WRITE "${OUTPUT}" "// Generated from ${INPUT} by OpalEmbedFile.cmake; do not edit.
#include \"${HEADER}\"
namespace opal::embedded
{
namespace
{
const std::uint32_t words[] = { ${words} };
}
Spirv ${FUNCTION}()
{
  return { words, ${word_count} };
}
}
")
else ()
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "'\\\\x\\1'," chars "${content}")
  file(WRITE "${OUTPUT}" "// Generated from ${INPUT} by OpalEmbedFile.cmake; do not edit.
#include \"${HEADER}\"
namespace opal::embedded
{
namespace
{
const char text[] = { ${chars} '\\0' };
}
const char* ${FUNCTION}()
{
  return text;
}
}
")
endif ()
