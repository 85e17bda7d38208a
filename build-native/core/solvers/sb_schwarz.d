build-native/core/solvers/sb_schwarz.o: core/solvers/sb_schwarz.c \
 core/solvers/sb_schwarz.h core/linalg/sb_sparse.h core/base/sb_common.h
core/solvers/sb_schwarz.h:
core/linalg/sb_sparse.h:
core/base/sb_common.h:
