# Writes OUT = a header defining HAIRFIT_SOURCE_FINGERPRINT, the SHA-256 of every file of lib/ and
# spec/ (paths and contents). The stage cache keys on it, so a rebuilt library with changed code
# never reuses values computed by the old code. The header is rewritten only when the fingerprint
# changes, so an unchanged tree recompiles nothing.
file(GLOB_RECURSE files RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/lib/*.cpp" "${SOURCE_DIR}/lib/*.h"
     "${SOURCE_DIR}/spec/*.cpp" "${SOURCE_DIR}/spec/*.h")
list(SORT files)
set(listing "")
foreach(f ${files})
  file(SHA256 "${SOURCE_DIR}/${f}" h)
  string(APPEND listing "${f} ${h}\n")
endforeach()
string(SHA256 fingerprint "${listing}")
set(text "#define HAIRFIT_SOURCE_FINGERPRINT \"${fingerprint}\"\n")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
endif()
if(NOT "${old}" STREQUAL "${text}")
  file(WRITE "${OUT}" "${text}")
endif()
