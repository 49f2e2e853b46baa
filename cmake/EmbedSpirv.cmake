# Turns a SPIR-V binary into a C++ source holding its 32-bit words.
file(READ ${SPV} hex HEX)
string(LENGTH "${hex}" hex_len)
math(EXPR rem "${hex_len} % 8")
if(NOT rem EQUAL 0 OR hex_len EQUAL 0)
  message(FATAL_ERROR "${SPV}: not a whole number of 32-bit words")
endif()
# SPIR-V is little-endian on disk; emit words as 0xDDCCBBAA from bytes AA BB CC DD.
string(REGEX REPLACE "(..)(..)(..)(..)" "0x\\4\\3\\2\\1u," words "${hex}")
math(EXPR count "${hex_len} / 8")
file(WRITE ${OUT} "#include <cstdint>\n#include <cstddef>\nextern const uint32_t nano_spv_${STEM}[] = {${words}};\nextern const std::size_t nano_spv_${STEM}_words = ${count};\n")
