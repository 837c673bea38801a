# SCULPT_SANITIZE=address,undefined (or thread) instruments every target.
# Undefined behaviour is made fatal so that a test run cannot pass over it.
if(SCULPT_SANITIZE)
  add_compile_options(-fsanitize=${SCULPT_SANITIZE} -fno-omit-frame-pointer -g)
  add_link_options(-fsanitize=${SCULPT_SANITIZE})
  if(SCULPT_SANITIZE MATCHES "undefined")
    add_compile_options(-fno-sanitize-recover=undefined)
  endif()
endif()
