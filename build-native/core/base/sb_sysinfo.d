build-native/core/base/sb_sysinfo.o: core/base/sb_sysinfo.c \
 build-native/build_id.h core/base/sb_sysinfo.h
build-native/build_id.h:
core/base/sb_sysinfo.h:
