# Project-wide warning set; RG_WERROR turns them into errors (CI does).
function(rg_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wconversion -Wno-sign-conversion -Wno-missing-field-initializers
    # GCC 12 reports std::variant members (rg::Value) as maybe-uninitialized in optimised builds: a known false positive.
    -Wno-maybe-uninitialized)
  if(RG_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
