# Text as a CMake list of its lines, for the scripts that read shader text line by line (emcv_port_hlsl.cmake,
# emcv_module_hlsl.cmake): the characters that CMake lists treat specially are parked as placeholders
# (; -> @EMCV_SEMICOLON@, [ -> @EMCV_LBRACKET@, ] -> @EMCV_RBRACKET@) before the split and put back after.

# out = text with ; [ ] parked.
function(emcv_park_text text out)
  string(REPLACE ";" "@EMCV_SEMICOLON@" t "${text}")
  string(REPLACE "[" "@EMCV_LBRACKET@" t "${t}")
  string(REPLACE "]" "@EMCV_RBRACKET@" t "${t}")
  set(${out} "${t}" PARENT_SCOPE)
endfunction()

# out = text parked (emcv_park_text) and split at its newlines: one list item per line.
function(emcv_text_lines text out)
  emcv_park_text("${text}" t)
  string(REPLACE "\n" ";" t "${t}")
  set(${out} "${t}" PARENT_SCOPE)
endfunction()

# out = parked text with ; [ ] put back.
function(emcv_unpark_text text out)
  string(REPLACE "@EMCV_SEMICOLON@" ";" t "${text}")
  string(REPLACE "@EMCV_LBRACKET@" "[" t "${t}")
  string(REPLACE "@EMCV_RBRACKET@" "]" t "${t}")
  set(${out} "${t}" PARENT_SCOPE)
endfunction()
