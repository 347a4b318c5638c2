# Warning and sanitizer settings for the project's own targets (never exported, never set at directory scope).
add_library(emcv_warnings INTERFACE)
target_compile_options(emcv_warnings INTERFACE
  -Wall -Wextra -Wconversion -Wsign-conversion -Wshadow -Wpedantic -Werror)

add_library(emcv_sanitize INTERFACE)
if(EMCV_SANITIZE)
  target_compile_options(emcv_sanitize INTERFACE -fsanitize=address,undefined -fno-sanitize-recover=all
                         -fno-omit-frame-pointer)
  target_link_options(emcv_sanitize INTERFACE -fsanitize=address,undefined)
endif()

# emcv_add_target_options(<target>): warnings as errors plus, when EMCV_SANITIZE is on, ASan/UBSan.
function(emcv_add_target_options target)
  target_link_libraries(${target} PRIVATE emcv_warnings emcv_sanitize)
endfunction()
