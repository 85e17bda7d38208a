build-native/core/linalg/sb_sparse.o: core/linalg/sb_sparse.c \
 core/linalg/sb_sparse.h core/base/sb_common.h
core/linalg/sb_sparse.h:
core/base/sb_common.h:
