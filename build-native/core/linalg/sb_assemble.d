build-native/core/linalg/sb_assemble.o: core/linalg/sb_assemble.c \
 core/linalg/sb_assemble.h core/base/sb_common.h
core/linalg/sb_assemble.h:
core/base/sb_common.h:
