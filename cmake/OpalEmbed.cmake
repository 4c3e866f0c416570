# opal_embed(<list-variable> <input> <function> <spirv|text> <header>): embeds a
# file of the source tree (or a generated one) into C++ as a function
# returning it (cmake/OpalEmbedFile.cmake writes the source at build time) and
# appends the generated source to <list-variable>.
function (opal_embed sources input function kind header)
  get_filename_component(name "${input}" NAME)
  set(output "${CMAKE_CURRENT_BINARY_DIR}/embedded/${name}.cxx")
  add_custom_command(
    OUTPUT "${output}"
    COMMAND "${CMAKE_COMMAND}" -DINPUT=${input} -DOUTPUT=${output} -DFUNCTION=${function} -DKIND=${kind}
            -DHEADER=${header} -P "${OPAL_CMAKE_DIR}/OpalEmbedFile.cmake"
    DEPENDS "${input}" "${OPAL_CMAKE_DIR}/OpalEmbedFile.cmake"
    COMMENT "Embedding ${name}"
    VERBATIM)
  set(${sources} ${${sources}} "${output}" PARENT_SCOPE)
endfunction ()
set(OPAL_CMAKE_DIR "${CMAKE_CURRENT_LIST_DIR}")
