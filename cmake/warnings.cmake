# One warning policy for every target and every preset.
add_compile_options(-Wall -Wextra -Wdouble-promotion -Werror)

# The portable core: no exceptions, no RTTI, single precision only.
function(ff_core_target target)
  target_compile_options(${target} PRIVATE
    $<$<COMPILE_LANGUAGE:CXX>:-fno-exceptions -fno-rtti>
    -fno-math-errno)
endfunction()
