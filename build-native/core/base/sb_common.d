build-native/core/base/sb_common.o: core/base/sb_common.c \
 core/base/sb_common.h
core/base/sb_common.h:
