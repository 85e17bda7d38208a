build-native/core/linalg/sb_galerkin.o: core/linalg/sb_galerkin.c \
 core/linalg/sb_galerkin.h core/linalg/sb_sparse.h core/base/sb_common.h
core/linalg/sb_galerkin.h:
core/linalg/sb_sparse.h:
core/base/sb_common.h:
