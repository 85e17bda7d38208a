build-native/core/base/sb_params.o: core/base/sb_params.c \
 core/base/sb_params.h core/base/sb_common.h
core/base/sb_params.h:
core/base/sb_common.h:
