# dp: depth peeling (src/core/alg_dp.c), exact: the image tests hold it to the
# reference's tolerance on every scene and both back ends, and to ll's image.
# Included by tests/CMakeLists.txt before the image tests (its lists are named there).
list(APPEND CANDIDATES "dp:dp")
list(APPEND EXACT_CANDIDATES dp)
list(APPEND AGREE_PAIRS "ll:dp")
list(APPEND MOD_CANDIDATES "dp:dp")
list(APPEND MOD_EXACT dp)
list(APPEND MOD_OSMESA_CANDIDATES "dp:dp")
