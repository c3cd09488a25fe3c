# Warnings and sanitizers applied to every target of the project (not to dependencies).
function(msp_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  if(MSP_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

if(MSP_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
