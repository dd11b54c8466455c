# ss_code_digest_header(SRC BIN OUT_HEADER): the build rule for
# BIN/generated/ss_code_digest.h, SS_CODE_DIGEST of every file that decides a
# reference run's result (the core, the shared headers, the public headers and
# the lab's runs and scenes of the source tree SRC), remade when one changes.
# The reference cache keys on it (src/lab/ss_reference.h). Sets OUT_HEADER to
# the header's path: add it to the sources of the target that includes it and
# BIN/generated to that target's include directories. Used by the project and
# by the fuzzers' project (tests/fuzz), which compiles the lab itself.
function(ss_code_digest_header SRC BIN OUT_HEADER)
  file(GLOB files CONFIGURE_DEPENDS
       ${SRC}/src/core/*.[ch] ${SRC}/src/common/*.h ${SRC}/include/skin_sim/*.h
       ${SRC}/src/lab/*.[ch])
  string(REPLACE ";" "\n" lines "${files}")
  file(WRITE ${BIN}/generated/code_digest_files.txt.in "${lines}\n")
  configure_file(${BIN}/generated/code_digest_files.txt.in
                 ${BIN}/generated/code_digest_files.txt COPYONLY)
  add_custom_command(
    OUTPUT ${BIN}/generated/ss_code_digest.h
    COMMAND ${CMAKE_COMMAND} -DLIST=${BIN}/generated/code_digest_files.txt -DROOT=${SRC}
            -DOUT=${BIN}/generated/ss_code_digest.h -P ${SRC}/cmake/code_digest.cmake
    DEPENDS ${files} ${BIN}/generated/code_digest_files.txt ${SRC}/cmake/code_digest.cmake
    COMMENT "digest of the simulation code (the reference cache's key)")
  set(${OUT_HEADER} ${BIN}/generated/ss_code_digest.h PARENT_SCOPE)
endfunction()
