# ddp: dual depth peeling (src/core/alg_ddp.c), exact: held to the reference's
# tolerance and to ll's image. Included by tests/CMakeLists.txt before the image tests.
list(APPEND CANDIDATES "ddp:ddp")
list(APPEND EXACT_CANDIDATES ddp)
list(APPEND AGREE_PAIRS "ll:ddp")
list(APPEND MOD_CANDIDATES "ddp:ddp")
list(APPEND MOD_EXACT ddp)
