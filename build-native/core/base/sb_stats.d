build-native/core/base/sb_stats.o: core/base/sb_stats.c \
 core/base/sb_stats.h core/base/sb_common.h
core/base/sb_stats.h:
core/base/sb_common.h:
